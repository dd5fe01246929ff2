//! What the actuator rule's findings are named, which attribute each blames, and
//! what to do about each, by MuJoCo's message.

/// (MuJoCo's message starts with, check name, attribute at fault, what to do).
type Fix = (&'static str, &'static str, Option<&'static str>, &'static str);

const FIXES: &[Fix] = &[
    (
        "kv and dampratio",
        "actuator-kv-and-dampratio",
        Some("dampratio"),
        "give kv or dampratio, not both",
    ),
    ("kv cannot", "actuator-kv-negative", Some("kv"), "give kv zero or more"),
    (
        "dampratio cannot",
        "actuator-dampratio-negative",
        Some("dampratio"),
        "give dampratio zero or more",
    ),
    (
        "timeconst cannot",
        "actuator-timeconst-negative",
        Some("timeconst"),
        "give timeconst zero or more",
    ),
    (
        "ctrlrange and inheritrange",
        "actuator-inheritrange-and-range",
        Some("inheritrange"),
        "give ctrlrange or inheritrange, not both",
    ),
    (
        "actrange and inheritrange",
        "actuator-inheritrange-and-range",
        Some("inheritrange"),
        "give actrange or inheritrange, not both",
    ),
    (
        "posrange and inheritrange",
        "actuator-inheritrange-and-range",
        Some("inheritrange"),
        "give posrange or inheritrange, not both",
    ),
    ("slewmax cannot", "actuator-pid-slewmax", Some("slewmax"), "give slewmax zero or more"),
    (
        "damper control range",
        "actuator-damper-ctrlrange",
        Some("ctrlrange"),
        "give the damper a control range of zero or more",
    ),
    ("damping coefficient", "actuator-damper-kv", Some("kv"), "give kv zero or more"),
    ("adhesion gain", "actuator-adhesion-gain", Some("gain"), "give gain zero or more"),
    (
        "adhesion control range",
        "actuator-adhesion-ctrlrange",
        Some("ctrlrange"),
        "give the adhesion a control range of zero or more",
    ),
    (
        "muscle tausmooth",
        "actuator-muscle-tausmooth",
        Some("tausmooth"),
        "give tausmooth zero or more",
    ),
    (
        "DC motor: motor constants",
        "actuator-dcmotor-motorconst",
        Some("motorconst"),
        "give motorconst values of zero or more",
    ),
    (
        "DC motor: motor constant K",
        "actuator-dcmotor-motorconst",
        Some("motorconst"),
        "give a positive motorconst (or nominal voltage and speed)",
    ),
    (
        "DC motor: resistance",
        "actuator-dcmotor-resistance",
        Some("resistance"),
        "give a positive resistance (or nominal voltage and torque)",
    ),
    (
        "DC motor: inductance",
        "actuator-dcmotor-inductance",
        Some("inductance"),
        "give an inductance of zero or more",
    ),
    (
        "DC motor: electrical",
        "actuator-dcmotor-inductance",
        Some("inductance"),
        "give a time constant of zero or more",
    ),
    (
        "cranklength and slidersite",
        "actuator-slidercrank-only",
        None,
        "remove cranklength and slidersite, or drive a cranksite",
    ),
    (
        "refsite can only",
        "actuator-refsite-site-only",
        Some("refsite"),
        "remove refsite, or drive a site",
    ),
    (
        "user has more values",
        "actuator-user-length",
        Some("user"),
        "give at most <size nuser_actuator> user values",
    ),
    (
        "missing transmission target",
        "actuator-no-target",
        None,
        "give it a joint, tendon, site, body or cranksite",
    ),
    (
        "missing base site",
        "actuator-slidercrank-slidersite",
        Some("slidersite"),
        "give the slider-crank a slidersite",
    ),
    (
        "crank length",
        "actuator-slidercrank-cranklength",
        Some("cranklength"),
        "give a positive cranklength",
    ),
    (
        "gaintype and biastype must both be 'so3'",
        "actuator-so3",
        Some("gaintype"),
        "give gaintype and biastype so3 together (or use <orientation>)",
    ),
    (
        "so3 requires dyntype",
        "actuator-so3",
        Some("dyntype"),
        "use dyntype none or integrator with so3",
    ),
    (
        "so3 requires gainprm",
        "actuator-so3",
        Some("biasprm"),
        "give biasprm[1] the negative of gainprm[0]",
    ),
    ("so3 site transmission", "actuator-so3", Some("refsite"), "give the site a refsite"),
    ("so3 joint transmission", "actuator-so3", Some("joint"), "drive a ball joint"),
    ("so3 requires site", "actuator-so3", None, "drive a site (with a refsite) or a ball joint"),
    ("so3 integrator", "actuator-so3", Some("actdim"), "give actdim 3 or none"),
    ("so3 quat input", "actuator-so3", Some("input"), "use input expmap, or dyntype none"),
    ("so3 input must", "actuator-so3", Some("input"), "use input expmap or quat"),
    ("so3 forcerange", "actuator-so3", Some("forcerange"), "give forcerange a lower bound of 0"),
    (
        "pid requires biastype",
        "actuator-pid",
        Some("biastype"),
        "give biastype affine (or use <pid>)",
    ),
    (
        "pid requires dyntype",
        "actuator-pid",
        Some("dyntype"),
        "use dyntype none or pid with a pid gain",
    ),
    ("ki (gainprm[0])", "actuator-pid", Some("gainprm"), "give dyntype pid, or gainprm[0] 0"),
    ("pid cannot use body", "actuator-pid", Some("body"), "drive a joint, tendon or site"),
    ("imax (dynprm[0])", "actuator-pid", Some("imax"), "give imax zero or more"),
    ("slewmax (dynprm[1])", "actuator-pid", Some("slewmax"), "give slewmax zero or more"),
    (
        "pid controller states require matching",
        "actuator-pid",
        Some("actdim"),
        "give actdim as many states as ki and slewmax make, or none",
    ),
    ("pid inputs", "actuator-pid", Some("input"), "use inputs among pos, vel, ff"),
    (
        "fixed and affine gains take one input",
        "actuator-input",
        Some("input"),
        "give one input (pos, vel or pressure), or none",
    ),
    (
        "input is not available for muscle",
        "actuator-input",
        Some("input"),
        "remove input: muscle and user gains take none",
    ),
    (
        "pid controller states require the pos",
        "actuator-pid",
        Some("input"),
        "add the pos input, or drop ki and slewmax",
    ),
    (
        "dcmotor controller inputs",
        "actuator-dcmotor-controller",
        Some("motorconst"),
        "give a positive motor constant",
    ),
    (
        "dcmotor controller gains",
        "actuator-dcmotor-controller",
        Some("input"),
        "add a pos, vel or ff input, or drop the controller gains",
    ),
    (
        "dcmotor integral gain",
        "actuator-dcmotor-controller",
        Some("input"),
        "add the pos input, or drop the integral gain",
    ),
    (
        "dcmotor slew rate",
        "actuator-dcmotor-controller",
        Some("input"),
        "add a pos, vel or ff input, or drop the slew limit",
    ),
    ("dyntype 'pid' requires", "actuator-pid", Some("dyntype"), "give gaintype pid (or use <pid>)"),
    (
        "damping requires",
        "actuator-damping-target",
        Some("damping"),
        "remove damping, or drive a joint or tendon",
    ),
    (
        "armature requires",
        "actuator-armature-target",
        Some("armature"),
        "remove armature, or drive a joint or tendon",
    ),
    (
        "inheritrange only available",
        "actuator-inheritrange",
        Some("inheritrange"),
        "use inheritrange with a position or intvelocity servo",
    ),
    (
        "inheritrange can only be used with hinge",
        "actuator-inheritrange",
        Some("inheritrange"),
        "use inheritrange with a hinge or slide joint",
    ),
    (
        "inheritrange can only be used with joint",
        "actuator-inheritrange",
        Some("inheritrange"),
        "use inheritrange with a joint or tendon",
    ),
    (
        "inheritrange used but",
        "actuator-inheritrange",
        Some("inheritrange"),
        "give the target a range, or remove inheritrange",
    ),
    (
        "actrange specified",
        "actuator-actrange-stateless",
        Some("actrange"),
        "remove actrange, or give a dyntype",
    ),
    ("actdim > 1", "actuator-actdim", Some("actdim"), "give actdim 1, or dyntype user"),
    ("invalid actdim 1", "actuator-actdim", Some("actdim"), "remove actdim, or give a dyntype"),
    ("invalid actdim 0", "actuator-actdim", Some("actdim"), "remove actdim, or give dyntype none"),
    ("actearly cannot", "actuator-dcmotor-actearly", Some("actearly"), "give actearly true"),
    ("range[0]<range[1]", "actuator-muscle", Some("range"), "give range an increasing pair"),
    ("lmin<1<lmax", "actuator-muscle", Some("lmin"), "give lmin below 1 and lmax above 1"),
    (
        "positive scale",
        "actuator-muscle",
        None,
        "give scale, vmax, fpmax and fvmax positive values",
    ),
    ("setting delay", "actuator-history", Some("delay"), "give nsample too, or remove delay"),
    (
        "history and delay require",
        "actuator-history",
        Some("nsample"),
        "give the actuator an input, or remove nsample and delay",
    ),
    ("at most 2^24", "actuator-history", Some("nsample"), "give nsample at most 16777216"),
    (
        "history buffers require",
        "actuator-history",
        Some("nsample"),
        "give <option timestep> a positive value",
    ),
];

/// The check name, attribute and fix for MuJoCo's message `mujoco`.
pub(super) fn fix_for(mujoco: &str) -> (&'static str, Option<&'static str>, &'static str) {
    FIXES
        .iter()
        .find(|(start, ..)| mujoco.starts_with(start))
        .map_or(("actuator", None, "make the actuator's values agree as MuJoCo asks"), |f| {
            (f.1, f.2, f.3)
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_message_has_its_own_fix() {
        assert_eq!(fix_for("kv cannot be negative").1, Some("kv"));
        assert_eq!(
            fix_for("ki (gainprm[0]) requires dyntype 'pid' in actuator 'a'").0,
            "actuator-pid"
        );
        // The prefixes are distinct: none hides a later one.
        for (i, (a, ..)) in FIXES.iter().enumerate() {
            for (b, ..) in &FIXES[i + 1..] {
                assert!(!b.starts_with(a), "{a} hides {b}");
            }
        }
    }
}
