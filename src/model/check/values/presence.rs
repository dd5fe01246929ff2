//! The presence rules of MuJoCo's XML schema: which of an element's attributes
//! exclude each other, go together, or are needed (MuJoCo 4.0.0's reader checks them
//! on the element as written, its classes aside: "Schema violation: at most one of
//! 'fovy', 'sensorsize' can be specified"). One table, [`RULES`], read from MuJoCo's
//! grammar (its schema's `exclusive`, `together` and `oneof` lines).

use crate::schema::ElementKind;

use super::{At, Check, Found, found_element, on};

/// What a rule asks of its bundles (each a list of attributes; a bundle is present
/// when any of its attributes is, complete when all are).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Presence {
    /// At most one bundle present.
    Exclusive,
    /// Every attribute, or none.
    Together,
    /// At least one bundle complete.
    OneOf,
}

use Presence::{Exclusive, OneOf, Together};

/// One rule: the elements (by schema path, as [`on::at`] reads it), what it asks, and
/// its bundles.
struct Rule {
    paths: &'static [&'static str],
    presence: Presence,
    bundles: &'static [&'static [&'static str]],
}

/// The frame sensors that take a frame of reference.
const FRAME_SENSORS: &[&str] = &[
    "sensor/framepos",
    "sensor/framequat",
    "sensor/framexaxis",
    "sensor/frameyaxis",
    "sensor/framezaxis",
    "sensor/framelinvel",
    "sensor/frameangvel",
];

/// The sensors between two geoms or bodies.
const PAIR_SENSORS: &[&str] = &["sensor/distance", "sensor/normal", "sensor/fromto"];

/// Every presence rule of MuJoCo 4.0.0, in its order (an element's first rule broken
/// is the one MuJoCo names).
const RULES: &[Rule] = &[
    Rule { paths: &["size"], presence: Exclusive, bundles: &[&["memory"], &["nstack"]] },
    Rule { paths: &["size"], presence: Exclusive, bundles: &[&["memory"], &["njmax"]] },
    Rule {
        paths: &["default/camera", "(world)body/camera"],
        presence: Exclusive,
        bundles: &[&["fovy"], &["sensorsize"]],
    },
    Rule {
        paths: &["default/light", "(world)body/light"],
        presence: Exclusive,
        bundles: &[&["directional"], &["type"]],
    },
    Rule { paths: &["asset/mesh"], presence: Exclusive, bundles: &[&["builtin"], &["file"]] },
    Rule { paths: &["asset/mesh"], presence: Exclusive, bundles: &[&["builtin"], &["vertex"]] },
    Rule {
        paths: &["(world)body/inertial"],
        presence: Exclusive,
        bundles: &[
            &["fullinertia"],
            &["quat"],
            &["axisangle"],
            &["xyaxes"],
            &["zaxis"],
            &["euler"],
        ],
    },
    Rule { paths: &["(world)body/attach"], presence: Exclusive, bundles: &[&["body"], &["frame"]] },
    Rule {
        paths: &["equality/connect"],
        presence: Exclusive,
        bundles: &[&["site1", "site2"], &["body1", "body2", "anchor"]],
    },
    Rule {
        paths: &["equality/connect"],
        presence: OneOf,
        bundles: &[&["site1", "site2"], &["body1", "anchor"]],
    },
    Rule { paths: &["equality/connect"], presence: Together, bundles: &[&["site1"], &["site2"]] },
    Rule {
        paths: &["equality/weld"],
        presence: Exclusive,
        bundles: &[&["site1", "site2"], &["body1", "body2", "anchor", "relpose"]],
    },
    Rule {
        paths: &["equality/weld"],
        presence: OneOf,
        bundles: &[&["site1", "site2"], &["body1"]],
    },
    Rule { paths: &["equality/weld"], presence: Together, bundles: &[&["site1"], &["site2"]] },
    Rule {
        paths: &["sensor/rangefinder"],
        presence: Exclusive,
        bundles: &[&["site"], &["camera"]],
    },
    Rule { paths: &["sensor/rangefinder"], presence: OneOf, bundles: &[&["site"], &["camera"]] },
    Rule { paths: FRAME_SENSORS, presence: Together, bundles: &[&["reftype"], &["refname"]] },
    Rule { paths: PAIR_SENSORS, presence: Exclusive, bundles: &[&["geom1"], &["body1"]] },
    Rule { paths: PAIR_SENSORS, presence: OneOf, bundles: &[&["geom1"], &["body1"]] },
    Rule { paths: PAIR_SENSORS, presence: Exclusive, bundles: &[&["geom2"], &["body2"]] },
    Rule { paths: PAIR_SENSORS, presence: OneOf, bundles: &[&["geom2"], &["body2"]] },
    Rule {
        paths: &["sensor/contact"],
        presence: Exclusive,
        bundles: &[&["geom1"], &["body1"], &["subtree1"], &["site"]],
    },
    Rule {
        paths: &["sensor/contact"],
        presence: Exclusive,
        bundles: &[&["geom2"], &["body2"], &["subtree2"]],
    },
    Rule { paths: &["sensor/user"], presence: Together, bundles: &[&["objtype"], &["objname"]] },
];

/// The rules of elements of `kind`.
fn rules_of(kind: ElementKind) -> impl Iterator<Item = &'static Rule> {
    RULES.iter().filter(move |r| r.paths.iter().any(|p| on::at(kind, p)))
}

pub(crate) const CHECKS: &[Check] = &[Check {
    name: "schema-presence",
    on: |k| rules_of(k).next().is_some(),
    test: first_broken,
    fix: "give the attributes MuJoCo's schema asks together, and only one of those it \
          takes one of",
}];

/// MuJoCo's message for the first rule the element breaks.
fn first_broken(at: &At<'_, '_>) -> Option<Found> {
    let kind = at.kind();
    // The schema reads the element's own attributes (its classes' are not given).
    let given = |a: &str| at.own(a).is_some();
    for rule in rules_of(kind) {
        let any = |b: &[&str]| b.iter().any(|a| given(a));
        let all = |b: &[&str]| b.iter().all(|a| given(a));
        let list = bundle_list(rule.bundles);
        let broken = match rule.presence {
            Exclusive => (rule.bundles.iter().filter(|b| any(b)).count() > 1)
                .then(|| format!("at most one of {list} can be specified")),
            Together => {
                let attrs = || rule.bundles.iter().flat_map(|b| b.iter());
                let n = attrs().filter(|a| given(a)).count();
                (n != 0 && n != attrs().count())
                    .then(|| format!("attributes {list} must be specified together"))
            }
            OneOf => (!rule.bundles.iter().any(|b| all(b)))
                .then(|| format!("one of {list} must be specified")),
        };
        if let Some(text) = broken {
            return found_element(format!("Schema violation: {text}"));
        }
    }
    None
}

/// The bundles as MuJoCo lists them: `'a'` for one attribute, `('a', 'b')` for more,
/// joined by `, `.
fn bundle_list(bundles: &[&[&str]]) -> String {
    let quoted = |b: &[&str]| b.iter().map(|a| format!("'{a}'")).collect::<Vec<_>>().join(", ");
    bundles
        .iter()
        .map(|b| if b.len() == 1 { quoted(b) } else { format!("({})", quoted(b)) })
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;
    use super::*;

    #[test]
    fn every_path_of_the_table_names_an_element_kind() {
        for rule in RULES {
            for path in rule.paths {
                assert!(ElementKind::all().any(|k| on::at(k, path)), "{path}");
                for b in rule.bundles.iter().flat_map(|b| b.iter()) {
                    assert!(
                        ElementKind::all()
                            .filter(|k| on::at(*k, path))
                            .all(|k| k.attr_index(b).is_some()),
                        "{path} {b}"
                    );
                }
            }
        }
    }

    /// The table is MuJoCo's own: every presence rule of its schema
    /// (`schema/mjcf-schema-facts.tsv`, derived from `src/xml/mjcf.schema`) over
    /// attributes the element reads, and nothing else. Left out: the orientation
    /// alternatives of a body, frame, geom, site or camera, a `variant` group in the
    /// schema, which MuJoCo 4.0.0 refuses in its own words ("multiple orientation
    /// specifiers are not allowed": the `orient` checks).
    #[test]
    fn the_table_is_the_schema_s_presence_rules() {
        let facts = include_str!("../../../../schema/mjcf-schema-facts.tsv");
        let variant = "quat axisangle xyaxes zaxis euler";
        let mut theirs = std::collections::BTreeSet::new();
        for line in facts.lines().filter(|l| !l.starts_with('#')).skip(1) {
            let f: Vec<&str> = line.split('\t').collect();
            let [parent, element, "", rule, bundles] = f[..] else { continue };
            if bundles == variant {
                continue;
            }
            let path = if parent == "mujoco" {
                element.to_string()
            } else {
                format!("{parent}/{element}")
            };
            let reads = |a: &str| {
                ElementKind::all().filter(|k| on::at(*k, &path)).any(|k| k.attr_index(a).is_some())
            };
            if !bundles.split([' ', '+']).all(reads) {
                continue; // attributes a default class cannot set
            }
            theirs.insert((path, rule.to_string(), bundles.to_string()));
        }
        let mut ours = std::collections::BTreeSet::new();
        for r in RULES {
            let rule = match r.presence {
                Exclusive => "exclusive",
                Together => "together",
                OneOf => "oneof",
            };
            let bundles: Vec<String> = r.bundles.iter().map(|b| b.join("+")).collect();
            for path in r.paths {
                ours.insert((path.to_string(), rule.to_string(), bundles.join(" ")));
            }
        }
        assert!(theirs.len() >= 35, "{theirs:?}");
        assert_eq!(ours, theirs);
    }

    #[test]
    fn bundles_are_listed_in_mujoco_s_words() {
        assert_eq!(bundle_list(&[&["fovy"], &["sensorsize"]]), "'fovy', 'sensorsize'");
        assert_eq!(bundle_list(&[&["site1", "site2"], &["body1"]]), "('site1', 'site2'), 'body1'");
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn the_schema_s_presence_rules_are_judged_on_the_element_as_written() {
        let w = |body: &str| format!("<mujoco><worldbody>{body}</worldbody></mujoco>");
        let things = r#"<body name="a"><geom name="g" size="1"/><site name="s"/></body><body name="b"><geom name="h" size="1"/></body><site name="t"/><camera name="c"/><frame name="f"/>"#;
        let with =
            |section: &str| format!("<mujoco><worldbody>{things}</worldbody>{section}</mujoco>");
        let pairs: Vec<(String, String)> = vec![
            (w(r#"<camera fovy="45" sensorsize="1 1"/>"#), w(r#"<camera fovy="45"/>"#)),
            (
                r#"<mujoco><default><camera fovy="45" sensorsize="1 1"/></default></mujoco>"#.into(),
                r#"<mujoco><default><camera sensorsize="1 1"/></default><worldbody><camera fovy="45"/></worldbody></mujoco>"#.into(),
            ),
            (w(r#"<light directional="true" type="spot"/>"#), w(r#"<light directional="false"/>"#)),
            (
                r#"<mujoco><default><light directional="true" type="spot"/></default></mujoco>"#.into(),
                r#"<mujoco><default><light type="spot"/></default></mujoco>"#.into(),
            ),
            (
                r#"<mujoco><asset><mesh name="m" builtin="sphere" params="1" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/></asset></mujoco>"#.into(),
                r#"<mujoco><asset><mesh name="m" builtin="sphere" params="1"/></asset></mujoco>"#.into(),
            ),
            (
                w(r#"<body><inertial pos="0 0 0" mass="1" fullinertia="1 1 1 0 0 0" quat="1 0 0 0"/></body>"#),
                w(r#"<body><inertial pos="0 0 0" mass="1" fullinertia="1 1 1 0 0 0"/></body>"#),
            ),
            (
                w(r#"<body><inertial pos="0 0 0" mass="1" diaginertia="1 1 1" quat="1 0 0 0" euler="0 0 0"/></body>"#),
                w(r#"<body><inertial pos="0 0 0" mass="1" diaginertia="1 1 1" euler="0 0 0"/></body>"#),
            ),
            (
                w(&format!(r#"{things}<attach body="a" frame="f" prefix="p"/>"#)),
                w(&format!(r#"{things}<attach body="a" prefix="p"/>"#)),
            ),
            (
                with(r#"<equality><connect site1="s" site2="t" body1="a"/></equality>"#),
                with(r#"<equality><connect site1="s" site2="t"/></equality>"#),
            ),
            (
                with(r#"<equality><connect body2="a" anchor="0 0 0"/></equality>"#),
                with(r#"<equality><connect body1="a" anchor="0 0 0"/></equality>"#),
            ),
            (
                with(r#"<equality><weld site2="t" body1="a"/></equality>"#),
                with(r#"<equality><weld body1="a" relpose="0 0 0 1 0 0 0"/></equality>"#),
            ),
            (with(r#"<equality><weld body2="a"/></equality>"#), with(r#"<equality><weld body1="a"/></equality>"#)),
            (
                with(r#"<sensor><rangefinder site="s" camera="c"/></sensor>"#),
                with(r#"<sensor><rangefinder camera="c"/></sensor>"#),
            ),
            (with(r#"<sensor><rangefinder/></sensor>"#), with(r#"<sensor><rangefinder site="s"/></sensor>"#)),
            (
                with(r#"<sensor><framepos objtype="site" objname="s" refname="s"/></sensor>"#),
                with(r#"<sensor><framepos objtype="site" objname="s" reftype="body" refname="a"/></sensor>"#),
            ),
            (
                with(r#"<sensor><frameangvel objtype="site" objname="s" reftype="site"/></sensor>"#),
                with(r#"<sensor><frameangvel objtype="site" objname="s"/></sensor>"#),
            ),
            (with(r#"<sensor><distance geom2="h"/></sensor>"#), with(r#"<sensor><distance geom1="g" geom2="h"/></sensor>"#)),
            (
                with(r#"<sensor><normal geom1="g" body1="a" body2="b"/></sensor>"#),
                with(r#"<sensor><normal body1="a" body2="b"/></sensor>"#),
            ),
            (
                with(r#"<sensor><fromto geom1="g" geom2="h" body2="b"/></sensor>"#),
                with(r#"<sensor><fromto geom1="g" body2="b"/></sensor>"#),
            ),
            (
                with(r#"<sensor><contact site="s" subtree1="a"/></sensor>"#),
                with(r#"<sensor><contact site="s" subtree2="b"/></sensor>"#),
            ),
            (
                with(r#"<sensor><contact geom2="h" body2="b"/></sensor>"#),
                with(r#"<sensor><contact geom1="g" body2="b"/></sensor>"#),
            ),
            (
                with(r#"<sensor><user objtype="body" dim="1"/></sensor>"#),
                with(r#"<sensor><user objtype="body" objname="a" dim="1"/></sensor>"#),
            ),
            (
                r#"<mujoco><size memory="1M" nstack="10"/></mujoco>"#.into(),
                r#"<mujoco><size memory="1M" nconmax="10"/></mujoco>"#.into(),
            ),
            (
                r#"<mujoco><size memory="1M" njmax="10"/></mujoco>"#.into(),
                r#"<mujoco><size njmax="10" nstack="10"/></mujoco>"#.into(),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("schema-presence", &pairs);
    }
}
