//! The keys of every scenario table, declared once with their struct.
//!
//! [`table!`] declares a struct of [`super::raw`], whose fields are the
//! keys of one TOML table, and from the same declaration its
//! [`Table::KEYS`]: the key names in field order, with the field's doc
//! comment as help. serde's unknown-field message lists the same names in
//! the same order (a unit test checks it); they are the allowed keys and
//! the did-you-mean candidates of [`super::source`]. A new key is one field
//! (with its doc comment) in [`super::raw`].
//!
//! The keys that belong to one type of wall or region, or one kind of
//! insertion only, are listed here ([`WALL_TYPE_KEYS`],
//! [`REGION_TYPE_KEYS`], [`INSERT_KIND_KEYS`]); a unit test checks that
//! each is a key of its table.

/// One key of a scenario table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Key {
    /// The key as written in the file.
    pub name: &'static str,
    /// The doc comment of its field, lines joined (each starts with a
    /// space): what it sets, with its unit and default.
    pub doc: &'static str,
}

impl Key {
    /// What the key sets, with its unit and default.
    pub fn help(&self) -> &'static str {
        self.doc.trim()
    }
}

/// A scenario table: a struct of [`super::raw`] declared with [`table!`].
pub trait Table {
    /// Its keys, in field order (the order serde lists them in).
    const KEYS: &'static [Key];
}

/// Declares a scenario table: a `Deserialize` struct that refuses unknown
/// keys (`deny_unknown_fields`) and its [`Table`] implementation, from one
/// list of fields. Each field has a doc comment (its help), then
/// optionally `#[key = "type"]` where the key is not the field's name,
/// then any `#[serde(...)]` attributes.
///
/// `table! { struct { fields } [more fields] }` appends `more fields`
/// (the form [`contact_law_keys!`](super::raw) calls back with).
macro_rules! table {
    (
        $(#[doc = $sdoc:literal])+
        pub struct $name:ident { $($fields:tt)* }
        [ $($more:tt)* ]
    ) => {
        $crate::scenario::keys::table! {
            $(#[doc = $sdoc])+
            pub struct $name { $($fields)* $($more)* }
        }
    };
    (
        $(#[doc = $sdoc:literal])+
        pub struct $name:ident {
            $(
                $(#[doc = $doc:literal])+
                $(#[key = $key:literal])?
                $(#[serde($($attr:tt)*)])*
                pub $field:ident: $ty:ty,
            )*
        }
    ) => {
        $(#[doc = $sdoc])+
        #[derive(Debug, Clone, Default, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct $name {
            $(
                $(#[doc = $doc])+
                $(#[serde(rename = $key)])?
                $(#[serde($($attr)*)])*
                pub $field: $ty,
            )*
        }

        impl $crate::scenario::keys::Table for $name {
            const KEYS: &'static [$crate::scenario::keys::Key] = &[$(
                $crate::scenario::keys::Key {
                    name: $crate::scenario::keys::key_name!($field $($key)?),
                    doc: concat!($($doc),+),
                },
            )*];
        }
    };
}
pub(crate) use table;

/// The key of a field: its name, or the `#[key = "..."]` given.
macro_rules! key_name {
    ($field:ident) => {
        stringify!($field)
    };
    ($field:ident $key:literal) => {
        $key
    };
}
pub(crate) use key_name;

/// The keys that apply to one type (`type = "..."`) or kind (`kind = "..."`)
/// of a table only, in the order messages list them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KindKeys {
    /// The type or kind, as written in the file.
    pub kind: &'static str,
    /// The names of its own keys.
    pub keys: &'static [&'static str],
}

/// The keys of each `[[wall]]` type (the other keys of [`WALL_KEYS`] apply
/// to every wall).
pub const WALL_TYPE_KEYS: &[KindKeys] = &[
    KindKeys {
        kind: "plane",
        keys: &["point", "normal"],
    },
    KindKeys {
        kind: "cylinder",
        keys: &["point", "axis", "radius", "inside"],
    },
    KindKeys {
        kind: "box",
        keys: &["lo", "hi", "inside"],
    },
    KindKeys {
        kind: "mesh",
        keys: &["file", "scale", "rotation", "offset", "merge_angle"],
    },
];

/// The keys of each insertion `region` type (besides `type`).
pub const REGION_TYPE_KEYS: &[KindKeys] = &[
    KindKeys {
        kind: "box",
        keys: &["lo", "hi"],
    },
    KindKeys {
        kind: "cylinder",
        keys: &["base", "axis", "radius", "height"],
    },
];

/// The keys of each `[[insert]]` kind (besides `kind` and `stage`).
pub const INSERT_KIND_KEYS: &[KindKeys] = &[
    KindKeys {
        kind: "file",
        keys: &[
            "file",
            "template",
            "format",
            "orientation_frame",
            "force_flags",
            "torque_flags",
            "fixed",
            "driven",
        ],
    },
    KindKeys {
        kind: "pack",
        keys: &[
            "mix",
            "template",
            "count",
            "volume_fraction",
            "region",
            "seed",
            "velocity",
            "orientation",
            "max_attempts",
            "euler",
            "angular_velocity",
            "force_flags",
            "torque_flags",
            "fixed",
            "driven",
        ],
    },
    KindKeys {
        kind: "stream",
        keys: &[
            "mix",
            "template",
            "count",
            "region",
            "seed",
            "velocity",
            "orientation",
            "bodies_per_second",
            "kg_per_second",
            "start",
            "end",
            "max_attempts",
            "euler",
            "angular_velocity",
            "force_flags",
            "torque_flags",
            "fixed",
            "driven",
            "start_after",
        ],
    },
];

/// The keys of `kind` in `kinds` (none for a kind not listed).
pub fn kind_keys(kinds: &[KindKeys], kind: &str) -> &'static [&'static str] {
    kinds
        .iter()
        .find(|k| k.kind == kind)
        .map_or(&[], |k| k.keys)
}

/// Every key that belongs to some kinds only, each once, in the order the
/// kinds first name it: the order in which misplaced keys are reported.
pub fn kind_specific(kinds: &[KindKeys]) -> Vec<&'static str> {
    let mut out: Vec<&'static str> = Vec::new();
    for k in kinds.iter().flat_map(|k| k.keys) {
        if !out.contains(k) {
            out.push(k);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::raw::*;
    use super::*;
    use serde::de::DeserializeOwned;

    /// The field names serde accepts for `T`, from its unknown-field error.
    fn serde_fields<T: DeserializeOwned + std::fmt::Debug>() -> Vec<String> {
        let e = toml::from_str::<T>("not_a_key_of_any_table = 0").unwrap_err();
        let msg = e.message().to_string();
        let tail = msg
            .strip_prefix("unknown field `not_a_key_of_any_table`, expected ")
            .unwrap_or_else(|| panic!("unexpected serde message: {msg}"));
        tail.split('`')
            .skip(1)
            .step_by(2)
            .map(str::to_string)
            .collect()
    }

    fn names(t: &[Key]) -> Vec<String> {
        t.iter().map(|k| k.name.to_string()).collect()
    }

    /// `(name, keys, serde's fields)` of every table of the file.
    fn every_table() -> Vec<(&'static str, &'static [Key], Vec<String>)> {
        macro_rules! case {
            ($($raw:ident),*) => {
                vec![$((stringify!($raw), $raw::KEYS, serde_fields::<$raw>())),*]
            };
        }
        case!(
            RawScenario,
            RawSimulation,
            RawDomain,
            RawIntegrator,
            RawAddedMass,
            RawMaterial,
            RawContact,
            RawPair,
            RawTemplate,
            RawSize,
            RawComponent,
            RawMix,
            RawRegion,
            RawInsert,
            RawRotation,
            RawWall,
            RawWallChange,
            RawStage,
            RawBodyChange,
            RawEvery,
            RawTrajectory,
            RawOutput,
            RawFields,
            RawFlow,
            RawFluid
        )
    }

    #[test]
    fn every_table_lists_the_fields_of_its_raw_struct_in_order() {
        for (raw, table, fields) in every_table() {
            assert!(fields.len() > 1, "{raw}: serde listed {fields:?}");
            assert_eq!(
                names(table),
                fields,
                "the key table of {raw} vs its serde fields"
            );
            assert!(
                table.iter().all(|k| !k.help().is_empty()),
                "{raw}: every key has a help"
            );
        }
    }

    #[test]
    fn renamed_keys_are_the_names_serde_accepts() {
        let wall = names(RawWall::KEYS);
        assert!(wall.contains(&"type".to_string()) && !wall.contains(&"kind".to_string()));
        assert!(toml::from_str::<RawWall>("type = \"plane\"").is_ok());
        assert!(toml::from_str::<RawWall>("kind = \"plane\"").is_err());
    }

    #[test]
    fn contact_and_pair_share_the_contact_law_keys() {
        let contact = names(RawContact::KEYS);
        let pair = names(RawPair::KEYS);
        assert_eq!(pair[0], "materials");
        assert_eq!(pair[1..], contact[..], "[[pair]] = materials + [contact]");
        for (c, p) in RawContact::KEYS.iter().zip(&RawPair::KEYS[1..]) {
            assert_eq!(c.help(), p.help(), "{}: one help", c.name);
        }
        // the conversion copies every key
        let p: RawPair = toml::from_str(
            "materials = [\"a\", \"b\"]\nrestitution = 0.25\nfriction = 0.5\n\
             rolling_friction = 0.1\nlaw = \"linear\"\nkn = 1e5\nkt = 2e4\n\
             tensile = true\ncohesion = \"sjkr\"\ncohesion_energy_density = 3e5\n\
             surface_energy = 0.05\ntangential = \"liggghts\"\n",
        )
        .unwrap();
        let c = p.law();
        assert_eq!(c.restitution, Some(0.25));
        assert_eq!(c.law, Some(LawName::Linear));
        assert_eq!(
            format!("{p:?}").replace(
                "RawPair { materials: Some([\"a\", \"b\"]), ",
                "RawContact { "
            ),
            format!("{c:?}"),
            "law() copies every contact-law key"
        );
    }

    #[test]
    fn kind_keys_are_keys_of_their_table_and_kinds_are_accepted_values() {
        let cases: [(&str, &[Key], &[KindKeys], &str); 3] = [
            ("wall", RawWall::KEYS, WALL_TYPE_KEYS, "type"),
            ("region", RawRegion::KEYS, REGION_TYPE_KEYS, "type"),
            ("insert", RawInsert::KEYS, INSERT_KIND_KEYS, "kind"),
        ];
        for (what, table, kinds, tag) in cases {
            for k in kinds {
                for n in k.keys {
                    assert!(
                        table.iter().any(|t| t.name == *n),
                        "{what} {tag} \"{}\": '{n}' is not a key of the table",
                        k.kind
                    );
                }
                let text = format!("{tag} = \"{}\"", k.kind);
                let ok = match what {
                    "wall" => toml::from_str::<RawWall>(&text).is_ok(),
                    "region" => toml::from_str::<RawRegion>(&text).is_ok(),
                    _ => toml::from_str::<RawInsert>(&text).is_ok(),
                };
                assert!(ok, "{what}: {text} is not accepted");
            }
        }
        // every wall type and insert kind has its list
        for v in ["plane", "cylinder", "box", "mesh"] {
            assert!(!kind_keys(WALL_TYPE_KEYS, v).is_empty(), "wall type {v}");
        }
        for v in ["file", "pack", "stream"] {
            assert!(
                !kind_keys(INSERT_KIND_KEYS, v).is_empty(),
                "insert kind {v}"
            );
        }
    }

    #[test]
    fn kind_specific_keys_keep_the_first_order() {
        assert_eq!(
            kind_specific(WALL_TYPE_KEYS),
            [
                "point",
                "normal",
                "axis",
                "radius",
                "inside",
                "lo",
                "hi",
                "file",
                "scale",
                "rotation",
                "offset",
                "merge_angle"
            ]
        );
        assert_eq!(
            kind_specific(REGION_TYPE_KEYS),
            ["lo", "hi", "base", "axis", "radius", "height"]
        );
    }
}
