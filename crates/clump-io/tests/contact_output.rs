//! `[output] contacts`: the contact frames, the bodies' contact counts and
//! the contact network, read back by the `vtk` Python package (skipped with
//! a note when it is missing) and compared with the engine's contacts; the
//! network's forces checked against the engine's body forces (Newton's
//! third law and the gather's own sums).

mod post;

use clump_io::post::frame::{Frame, Side};
use glam::DVec3;
use serde_json::Value;

fn vec3s(v: &Value) -> Vec<DVec3> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| {
            let a: Vec<f64> = x
                .as_array()
                .unwrap()
                .iter()
                .map(|y| y.as_f64().unwrap())
                .collect();
            DVec3::new(a[0], a[1], a[2])
        })
        .collect()
}

fn nums(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|y| y.as_f64().unwrap())
        .collect()
}

#[test]
fn contact_frames_network_and_counts_match_the_engine() {
    let d = post::dir("contacts");
    let out = "vtk = { every = 0.05 }\ncontacts = { every = 0.05 }\nthermo = { every = 0.01 }";
    let r = post::run(&post::bed_text(120, 7, out), &d);
    let w = r.world();
    let frame = Frame::capture(w);
    let cs = frame
        .contacts
        .clone()
        .expect("the last step recorded its contacts");
    assert!(cs.len() > 150, "{} contacts", cs.len());
    let run = d.join("run");
    let step = w.step;
    let contacts_file = run.join(format!("contacts_{step:06}.vtp"));
    let bodies_file = run.join(format!("bodies_{step:06}.vtp"));
    assert!(contacts_file.exists() && bodies_file.exists());

    // the network: every body's force is the sum of its edges' forces, its
    // wall contacts' forces and its weight (the engine's gather sums them
    // in another order)
    let text = std::fs::read_to_string(run.join(format!("network_{step:06}.csv"))).unwrap();
    let index = frame.index_by_id();
    let mut f = vec![DVec3::ZERO; frame.bodies.len()];
    let mut edges = 0;
    for line in text.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let (i, j) = (index[&(v[0] as u64)], index[&(v[1] as u64)]);
        assert!(v[0] < v[1] && v[2] >= 1.0);
        let fe = DVec3::new(v[3], v[4], v[5]);
        f[i] += fe;
        f[j] -= fe;
        let branch = DVec3::new(v[6], v[7], v[8]);
        let l = clump_io::post::frame::min_image(
            &frame.domain,
            frame.bodies[j].position - frame.bodies[i].position,
        );
        assert!(
            (branch - l).length() < 1e-15 && l.length() < 0.0062,
            "branch {branch}"
        );
        edges += 1;
    }
    assert!(edges > 100);
    for c in &cs {
        if let Side::Wall(_) = c.partner {
            f[index[&c.body_i]] += c.force;
        }
    }
    let weight = frame.bodies[0].mass * 9.81;
    for (k, b) in frame.bodies.iter().enumerate() {
        let got = f[k] + b.mass * w.config.gravity;
        assert!(
            (got - b.force).length() <= 1e-6 * weight,
            "body {}: network {got} vs engine {}",
            b.id,
            b.force
        );
    }

    // the files, read by vtk
    let Some(j) = post::read_vtk(&[
        contacts_file.clone(),
        bodies_file.clone(),
        run.join("contacts.pvd"),
    ]) else {
        return;
    };
    let c = &j[contacts_file.to_str().unwrap()];
    assert_eq!(c["lines"].as_u64().unwrap() as usize, cs.len());
    assert_eq!(c["field_data"]["wall_names"], serde_json::json!(["floor"]));
    let cd = &c["cell_data"];
    let force = vec3s(&cd["force"]);
    let point = vec3s(&cd["contact_point"]);
    let pts = vec3s(&c["points"]);
    let (fnm, ftm, ovl) = (
        nums(&cd["force_normal"]),
        nums(&cd["force_tangential"]),
        nums(&cd["overlap"]),
    );
    let (bi, bj, wall, sliding) = (
        nums(&cd["body_i"]),
        nums(&cd["body_j"]),
        nums(&cd["wall"]),
        nums(&cd["sliding"]),
    );
    let mut n_sliding = 0;
    for (k, e) in cs.iter().enumerate() {
        assert_eq!(force[k], e.force);
        assert_eq!(point[k], e.point);
        assert_eq!((pts[2 * k], pts[2 * k + 1]), (e.centre_i, e.end_j));
        assert_eq!(fnm[k], e.normal_force());
        assert_eq!(ftm[k], e.tangential_force());
        assert_eq!(ovl[k], e.overlap);
        assert_eq!(bi[k] as u64, e.body_i);
        match e.partner {
            Side::Body(b) => assert!(bj[k] as u64 == b && wall[k] == -1.0),
            Side::Wall(x) => assert!(bj[k] == 0.0 && wall[k] == x as f64),
        }
        assert_eq!(sliding[k] == 1.0, e.sliding);
        n_sliding += e.sliding as usize;
        // the line joins the two sphere centres: its length is the sum of
        // the radii minus the overlap (a wall contact: radius minus overlap)
        let len = (e.centre_i - e.end_j).length();
        let expect = match e.partner {
            Side::Body(_) => 0.003 - e.overlap,
            Side::Wall(_) => 0.0015 - e.overlap,
        };
        assert!((len - expect).abs() < 1e-12, "{len} vs {expect}");
    }
    eprintln!("{} contacts, {n_sliding} sliding", cs.len());
    let b = &j[bodies_file.to_str().unwrap()];
    assert_eq!(
        b["field_data"]["template_names"],
        serde_json::json!(["dimer"])
    );
    let counts = clump_io::post::network::body_counts(&frame).unwrap();
    let pd = &b["point_data"];
    let (coord, nc, nw) = (
        nums(&pd["coordination"]),
        nums(&pd["contacts"]),
        nums(&pd["wall_contacts"]),
    );
    let bf = vec3s(&pd["force"]);
    for (k, body) in frame.bodies.iter().enumerate() {
        assert_eq!(counts[k].map(f64::from), [coord[k], nc[k], nw[k]]);
        assert_eq!(bf[k], body.force);
    }
    let mean = coord.iter().sum::<f64>() / coord.len() as f64;
    assert!(mean > 2.0, "mean coordination {mean}");
    let pvd = j[run.join("contacts.pvd").to_str().unwrap()]["datasets"]
        .as_array()
        .unwrap()
        .clone();
    assert!(pvd.len() >= 2);
    let last = pvd.last().unwrap();
    assert_eq!(last[1].as_str().unwrap(), format!("contacts_{step:06}.vtp"));
    assert_eq!(last[2]["lines"].as_u64().unwrap() as usize, cs.len());
    let _ = std::fs::remove_dir_all(&d);
}
