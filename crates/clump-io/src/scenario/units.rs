//! The SI unit of every numeric key, and hints for values written with units.

/// The SI unit of a key (`""` for dimensionless), if the key is numeric.
pub fn unit_of(key: &str) -> Option<&'static str> {
    Some(match key {
        "youngs_modulus" => "Pa",
        "density" | "fluid_density" => "kg/m^3",
        "poisson_ratio"
        | "restitution"
        | "friction"
        | "rolling_friction"
        | "dt_fraction"
        | "scale"
        | "fraction"
        | "volume_fraction"
        | "coefficient"
        | "min"
        | "max"
        | "mean"
        | "std"
        | "max_overlap_ratio"
        | "kinetic_energy_jump" => "",
        "kn" | "kt" => "N/m",
        "radius" | "spacing" | "edge" | "skin" | "height" | "lo" | "hi" | "point" | "center"
        | "base" | "spheres" | "offset" | "torque_point" => "m",
        "angle" | "merge_angle" => "deg",
        "mass" => "kg",
        "inertia" => "kg m^2",
        "dt" | "duration" | "every" | "start" | "end" => "s",
        "gravity" => "m/s^2",
        "velocity" | "surface_velocity" => "m/s",
        "angular_velocity" => "rad/s",
        "bodies_per_second" => "1/s",
        "kg_per_second" => "kg/s",
        "steps" | "every_steps" | "count" | "n" | "seed" | "max_attempts" => "",
        _ => return None,
    })
}

/// Factor to SI and the SI unit of common unit suffixes.
fn unit_factor(u: &str) -> Option<(f64, &'static str)> {
    Some(match u {
        "m" => (1.0, "m"),
        "cm" => (1e-2, "m"),
        "mm" => (1e-3, "m"),
        "um" | "µm" => (1e-6, "m"),
        "km" => (1e3, "m"),
        "kg" => (1.0, "kg"),
        "g" => (1e-3, "kg"),
        "mg" => (1e-6, "kg"),
        "t" => (1e3, "kg"),
        "s" => (1.0, "s"),
        "ms" => (1e-3, "s"),
        "us" | "µs" => (1e-6, "s"),
        "min" => (60.0, "s"),
        "Pa" => (1.0, "Pa"),
        "kPa" => (1e3, "Pa"),
        "MPa" => (1e6, "Pa"),
        "GPa" => (1e9, "Pa"),
        "kg/m3" | "kg/m^3" | "kg/m³" => (1.0, "kg/m^3"),
        "g/cm3" | "g/cm^3" | "g/cm³" => (1e3, "kg/m^3"),
        "m/s" => (1.0, "m/s"),
        "mm/s" => (1e-3, "m/s"),
        "cm/s" => (1e-2, "m/s"),
        "rad/s" => (1.0, "rad/s"),
        "rpm" => (std::f64::consts::TAU / 60.0, "rad/s"),
        "N/m" => (1.0, "N/m"),
        "kN/m" => (1e3, "N/m"),
        _ => return None,
    })
}

/// A hint for a value written as a string with a unit, e.g. `"5 mm"` for a
/// length: `help: Clump reads SI units: write 0.005 (5 mm in m)`.
pub fn unit_hint(key: &str, value_text: &str) -> Option<String> {
    let unit = unit_of(key)?;
    let v = value_text
        .trim()
        .trim_matches(|c| c == '"' || c == '\'')
        .trim();
    let split = v
        .find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E')))
        .unwrap_or(v.len());
    // "e" may start a unit; back off if the number does not parse
    let (mut num, mut suffix) = (v[..split].trim(), v[split..].trim());
    if num.parse::<f64>().is_err() && num.ends_with(['e', 'E']) {
        num = &num[..num.len() - 1];
        suffix = v[num.len()..].trim();
    }
    let x: f64 = num.parse().ok()?;
    if suffix.is_empty() {
        return Some(format!(
            "help: write the number without quotes: {key} = {num}"
        ));
    }
    let (f, si) = unit_factor(suffix)?;
    if !unit.is_empty() && si != unit {
        return Some(format!(
            "help: '{key}' is in {unit}, but the value has unit {suffix} ({si})"
        ));
    }
    Some(format!(
        "help: Clump reads SI units only: write {key} = {} ({v} in {si})",
        x * f
    ))
}
