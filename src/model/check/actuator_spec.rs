//! An actuator as MuJoCo 4.0.0's XML reader makes it (its `mjsActuator`): the
//! gain, bias and dynamics types and parameters the shortcuts (`<position kp>`,
//! `<pid ki>`, `<dcmotor motorconst>`, ...) derive, its ranges, and its
//! transmission, for the actuator checks to judge as MuJoCo's compiler does; and
//! what the reader itself refuses while making it.
//!
//! How a class's actuator defaults reach an actuator, as probed with MuJoCo 4.0.0
//! (its source and its behaviour differ here): the attributes every tag reads alike
//! (ranges, `gear`, `damping`, `armature`, `delay`, `nsample`, `user`,
//! `cranklength`) reach an actuator of any tag from a default of any tag; what a
//! shortcut derives (gains, types, `inheritrange`) reaches an actuator of the same
//! tag, and a `<general>` (a `<default><position kp="5" inheritrange="1"/>` gives a
//! `<general>` the position servo and its `inheritrange`, but leaves a `<motor>` a
//! plain motor and an `<intvelocity>` its own gains); a class's `actdim` reaches a
//! `<general>` only. Where the defaults of several tags set servos, a default of
//! another tag follows the servo's, or a class's `inheritrange` meets a range given
//! elsewhere, MuJoCo 4.0.0 mixes them in ways not followed here, and the actuator
//! is not judged ([`Read::Unknown`]).

use crate::model::Model;
use crate::model::tree::{ElementId, Node};
use crate::schema::Role;
use crate::value::Value;

/// `mjNGAIN`, `mjNBIAS`, `mjNDYN`: the length of the parameter arrays.
const NPRM: usize = 10;

/// A `*limited` keyword.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Limited {
    False,
    True,
    Auto,
}

/// The transmission type (`mjtTrn`), from the attribute that names the target.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Trn {
    Undefined,
    Joint,
    JointInParent,
    Tendon,
    SliderCrank,
    Site,
    Body,
}

/// `input` bits (`mjtInput`; `expmap` and `quat` are the chart values 1 and 2).
pub(crate) const INPUT_POS: i64 = 1;
pub(crate) const INPUT_VEL: i64 = 2;
pub(crate) const INPUT_FF: i64 = 4;
pub(crate) const INPUT_VOLTAGE: i64 = 8;
pub(crate) const INPUT_NONE: i64 = 16;
pub(crate) const INPUT_PRESSURE: i64 = 32;
/// The so3 charts.
pub(crate) const CHART_EXPMAP: i64 = 1;
pub(crate) const CHART_QUAT: i64 = 2;

/// The actuator's spec, as MuJoCo's reader leaves it.
#[derive(Clone, Debug)]
pub(crate) struct Spec<'m> {
    pub(crate) gaintype: &'static str,
    pub(crate) biastype: &'static str,
    pub(crate) dyntype: &'static str,
    pub(crate) gainprm: [f64; NPRM],
    pub(crate) biasprm: [f64; NPRM],
    pub(crate) dynprm: [f64; NPRM],
    pub(crate) ctrlrange: [f64; 2],
    pub(crate) forcerange: [f64; 2],
    pub(crate) actrange: [f64; 2],
    pub(crate) ctrllimited: Limited,
    pub(crate) forcelimited: Limited,
    pub(crate) actlimited: Limited,
    pub(crate) actdim: i64,
    pub(crate) inheritrange: f64,
    pub(crate) ctrlspec: i64,
    pub(crate) damping: [f64; 3],
    pub(crate) armature: f64,
    pub(crate) cranklength: f64,
    pub(crate) nsample: i64,
    pub(crate) delay: f64,
    /// How many `user` numbers it has.
    pub(crate) nuser: usize,
    pub(crate) actearly: bool,
    pub(crate) trn: Trn,
    /// The attribute naming its transmission target, and its value.
    pub(crate) target: Option<(&'static str, &'m Value)>,
    /// A `refsite` is given.
    pub(crate) refsite: bool,
    /// A `slidersite` is given.
    pub(crate) slidersite: bool,
}

impl Default for Spec<'_> {
    /// `mjs_defaultActuator`.
    fn default() -> Self {
        let mut gainprm = [0.0; NPRM];
        gainprm[0] = 1.0;
        let mut dynprm = [0.0; NPRM];
        dynprm[0] = 1.0;
        Spec {
            gaintype: "fixed",
            biastype: "none",
            dyntype: "none",
            gainprm,
            biasprm: [0.0; NPRM],
            dynprm,
            ctrlrange: [0.0; 2],
            forcerange: [0.0; 2],
            actrange: [0.0; 2],
            ctrllimited: Limited::Auto,
            forcelimited: Limited::Auto,
            actlimited: Limited::Auto,
            actdim: -1,
            inheritrange: 0.0,
            ctrlspec: 0,
            damping: [0.0; 3],
            armature: 0.0,
            cranklength: 0.0,
            nsample: 0,
            delay: 0.0,
            nuser: 0,
            actearly: false,
            trn: Trn::Undefined,
            target: None,
            refsite: false,
            slidersite: false,
        }
    }
}

/// What the reader made of an actuator: its spec, or MuJoCo's message refusing it.
pub(crate) enum Read<'m> {
    /// The spec.
    Made(Box<Spec<'m>>),
    /// The reader refuses it with this message.
    Refused(&'static str),
    /// A value this emulation does not read (an unknown `input` token, say): no
    /// judgement.
    Unknown,
}

/// The element's own attribute `attr`.
fn own<'m>(node: &'m Node, attr: &str) -> Option<&'m Value> {
    node.kind().attr_index(attr).and_then(|i| node.attr(i))
}

/// The numbers of `v`.
fn numbers(v: &Value) -> Option<Vec<f64>> {
    match v {
        Value::Float(x) => Some(vec![*x]),
        Value::Int(i) => Some(vec![*i as f64]),
        Value::Floats(v) => Some(v.to_vec()),
        Value::Ints(v) => Some(v.iter().map(|i| *i as f64).collect()),
        _ => None,
    }
}

/// Writes the element's numbers of `attr` over the first ones of `dst`, as MuJoCo's
/// `ReadAttr` does; whether it was given.
fn read_into(node: &Node, attr: &str, dst: &mut [f64]) -> bool {
    let Some(v) = own(node, attr).and_then(numbers) else { return false };
    for (d, x) in dst.iter_mut().zip(v) {
        *d = x;
    }
    true
}

/// The element's one number `attr`.
fn read_one(node: &Node, attr: &str) -> Option<f64> {
    own(node, attr).and_then(numbers).and_then(|v| v.first().copied())
}

/// The element's keyword `attr`.
fn keyword<'m>(node: &'m Node, attr: &str) -> Option<&'m str> {
    own(node, attr).and_then(Value::as_str)
}

/// A keyword as the static spelling MuJoCo's maps know.
fn known(k: &str, of: &[&'static str]) -> Option<&'static str> {
    of.iter().copied().find(|x| *x == k)
}

const DYN: &[&str] =
    &["none", "integrator", "filter", "filterexact", "muscle", "dcmotor", "pid", "user"];
const GAIN: &[&str] = &["fixed", "affine", "muscle", "dcmotor", "so3", "pid", "user"];
const BIAS: &[&str] = &["none", "affine", "muscle", "dcmotor", "so3", "user"];

fn limited(k: &str) -> Option<Limited> {
    match k {
        "false" => Some(Limited::False),
        "true" => Some(Limited::True),
        "auto" => Some(Limited::Auto),
        _ => None,
    }
}

/// What MuJoCo's reader refuses of an `input` text.
pub(crate) enum BadInput<'t> {
    /// A token that is no input ("invalid keyword").
    Unknown(&'t str),
    /// A token given twice ("duplicate keyword").
    Twice,
    /// Tokens out of their canonical order.
    OutOfOrder,
}

/// The input tokens, in their canonical order, with their signature bits (MuJoCo
/// 4.0.0's `mjtCtrlInput`; the source read has no `pressure`).
pub(crate) const INPUT_TOKENS: &[(&str, i64)] = &[
    ("pos", INPUT_POS),
    ("vel", INPUT_VEL),
    ("ff", INPUT_FF),
    ("voltage", INPUT_VOLTAGE),
    ("pressure", INPUT_PRESSURE),
];

/// The signature an `input` text spells, as MuJoCo's `ReadInputSpec` reads it: a
/// chart (`expmap`, `quat`) or `none` as the whole text, else tokens, each known and
/// given once, in canonical order.
pub(crate) fn parse_input(text: &str) -> Result<i64, BadInput<'_>> {
    match text {
        "expmap" => return Ok(CHART_EXPMAP),
        "quat" => return Ok(CHART_QUAT),
        "none" => return Ok(INPUT_NONE),
        _ => {}
    }
    let (mut spec, mut ordered) = (0, true);
    for word in text.split_ascii_whitespace() {
        let Some(&(_, bit)) = INPUT_TOKENS.iter().find(|(t, _)| *t == word) else {
            return Err(BadInput::Unknown(word));
        };
        if spec & bit != 0 {
            return Err(BadInput::Twice);
        }
        ordered &= bit > spec;
        spec |= bit;
    }
    if ordered { Ok(spec) } else { Err(BadInput::OutOfOrder) }
}

/// The `input` attribute as MuJoCo reads it: `None` when not given, `Some(None)` for
/// text it refuses.
fn input(node: &Node) -> Option<Option<i64>> {
    keyword(node, "input").map(|text| parse_input(text).ok())
}

/// The attributes every actuator tag reads alike, which a class's actuator default of
/// any tag gives an actuator of any tag (checked with MuJoCo 4.0.0 for the ranges,
/// `gear`, `damping`, `armature`, `delay`, `nsample`, `user` and `cranklength`).
const COMMON: &[&str] = &[
    "group",
    "nsample",
    "interp",
    "delay",
    "ctrlrange",
    "user",
    "ctrllimited",
    "forcelimited",
    "actlimited",
    "forcerange",
    "actrange",
    "lengthrange",
    "gear",
    "damping",
    "armature",
    "cranklength",
];

/// Whether a class's actuator default sets more than the [`COMMON`] attributes.
fn sets_more(d: &Node) -> bool {
    d.attrs().iter().any(|(i, _)| !COMMON.contains(&d.kind().attr(*i as usize).name))
}

/// The spec of the actuator `node` (of `model`, class in force `class`), its
/// classes' actuator defaults applied as the module docs say.
pub(crate) fn read<'m>(model: &'m Model, node: &'m Node, class: Option<ElementId>) -> Read<'m> {
    let mut spec = Spec::default();
    // The class chain, the root class first.
    let mut chain = Vec::new();
    let mut cur = class;
    while let Some(id) = cur {
        let Some(n) = model.node_by_id(id) else { break };
        chain.push(n);
        cur = model
            .index
            .parent(id)
            .filter(|p| model.node_by_id(*p).is_some_and(|n| n.kind().is(Role::DefaultClass)));
    }
    // Its actuator defaults, in MuJoCo's order; one without attributes is not written.
    let defaults: Vec<&Node> = chain
        .into_iter()
        .rev()
        .flat_map(|c| c.children().iter().filter(|d| d.kind().is(Role::DefaultActuator)))
        .filter(|d| !d.attrs().is_empty())
        .collect();
    let tag = node.kind().tag();
    // The tags whose defaults set a servo: any shortcut's for a `<general>` (it takes
    // what every default derives), else what sets more than the common attributes.
    let servo = |d: &Node| {
        let t = d.kind().tag();
        if tag == "general" { t != "general" || sets_more(d) } else { sets_more(d) }
    };
    let mut tags: Vec<&str> =
        defaults.iter().filter(|d| servo(d)).map(|d| d.kind().tag()).collect();
    tags.sort_unstable();
    tags.dedup();
    let followed = match tags[..] {
        [] => true,
        // A class's muscle reaches a muscle in ways not followed (MuJoCo 4.0.0
        // compiles a muscle whose class gives lmax 1 and which gives lmax -1).
        [t] => t == tag && tag != "muscle" || tag == "general",
        _ => false,
    };
    // A default of another tag after the servo's (even one giving only common
    // attributes) resets what MuJoCo 4.0.0 keeps of it (a `<motor gear>` after a
    // `<position inheritrange>` drops the `inheritrange`): not followed.
    let after_servo = tags.first().is_some_and(|servo_tag| {
        defaults
            .iter()
            .skip_while(|d| d.kind().tag() != *servo_tag)
            .any(|d| d.kind().tag() != *servo_tag)
    });
    if !followed || after_servo {
        return Read::Unknown;
    }
    let ranges = ["ctrlrange", "posrange", "actrange"];
    let mut class_range = false;
    for d in defaults {
        class_range |= ranges.iter().any(|a| own(d, a).is_some());
        // A default of another tag gives a shortcut only the common attributes.
        let read = if tag == "general" || d.kind().tag() == tag {
            one_actuator(&mut spec, d)
        } else {
            general_attributes(&mut spec, d)
        };
        // A class that MuJoCo refuses is refused whatever uses it: not judged here.
        if read.is_err() {
            return Read::Unknown;
        }
    }
    // MuJoCo 4.0.0 lets the range or `inheritrange` given last stand over the other
    // (a class's range gives way to the element's `inheritrange`, the class's
    // `inheritrange` to the element's range): not followed here.
    let own_inherit = own(node, "inheritrange").is_some();
    let own_range = ranges.iter().any(|a| own(node, a).is_some());
    let inherit = spec.inheritrange != 0.0 || own_inherit;
    if inherit && (class_range || spec.inheritrange != 0.0 && !own_inherit && own_range) {
        return Read::Unknown;
    }
    match one_actuator(&mut spec, node) {
        Ok(()) => Read::Made(Box::new(spec)),
        Err(Some(msg)) => Read::Refused(msg),
        Err(None) => Read::Unknown,
    }
}

/// MuJoCo's `OneActuator`: the element's attributes written over `spec`; `Err` with
/// MuJoCo's message when the reader refuses them, `Err(None)` when this emulation
/// cannot tell.
fn one_actuator<'m>(spec: &mut Spec<'m>, node: &'m Node) -> Result<(), Option<&'static str>> {
    let tag = node.kind().tag();
    if tag != "general" {
        spec.actdim = -1;
    }
    general_attributes(spec, node)?;
    transmission(spec, node)?;
    // A shortcut clears the input signature a class's `<general input>` gave, in a
    // class as on an element (MuJoCo 4.0.0: a class's `<general input="ff">` then
    // `<position>` leaves a `<general>` of that class no input; the other order
    // gives it `ff`). The signature MuJoCo then compiles for the shortcut (`pos` for
    // a position servo, `pressure` for a cylinder) is one its gains take.
    match tag {
        "general" | "orientation" | "pid" | "dcmotor" => {}
        _ => spec.ctrlspec = 0,
    }
    match tag {
        "general" => {
            if let Some(i) = input(node) {
                spec.ctrlspec = i.ok_or(None)?;
            }
            if let Some(r) = read_one(node, "inheritrange") {
                spec.inheritrange = r;
            }
            Ok(())
        }
        "motor" => {
            spec.gainprm[0] = 1.0;
            (spec.dyntype, spec.gaintype, spec.biastype) = ("none", "fixed", "none");
            Ok(())
        }
        "position" | "intvelocity" => position(spec, node, tag == "intvelocity"),
        "orientation" => orientation(spec, node),
        "pid" => pid(spec, node),
        "velocity" => {
            let kv = read_one(node, "kv").unwrap_or(spec.gainprm[0]);
            spec.biasprm = [0.0; NPRM];
            spec.gainprm[0] = kv;
            spec.biasprm[2] = -kv;
            (spec.dyntype, spec.gaintype, spec.biastype) = ("none", "fixed", "affine");
            Ok(())
        }
        "damper" => damper(spec, node),
        "cylinder" => cylinder(spec, node),
        "muscle" => muscle(spec, node),
        "adhesion" => adhesion(spec, node),
        "dcmotor" => dcmotor(spec, node),
        // A plugin actuator: not judged.
        _ => Err(None),
    }
}

/// The attributes every actuator tag reads into the spec (MuJoCo's `kGeneralAttrs`).
fn general_attributes(spec: &mut Spec<'_>, node: &Node) -> Result<(), Option<&'static str>> {
    if let Some(n) = read_one(node, "nsample") {
        spec.nsample = n as i64;
    }
    if let Some(d) = read_one(node, "delay") {
        spec.delay = d;
    }
    read_into(node, "ctrlrange", &mut spec.ctrlrange);
    read_into(node, "forcerange", &mut spec.forcerange);
    read_into(node, "actrange", &mut spec.actrange);
    if let Some(v) = own(node, "user").and_then(numbers) {
        spec.nuser = v.len();
    }
    for (attr, slot) in [
        ("ctrllimited", &mut spec.ctrllimited),
        ("forcelimited", &mut spec.forcelimited),
        ("actlimited", &mut spec.actlimited),
    ] {
        if let Some(k) = keyword(node, attr) {
            *slot = limited(k).ok_or(None)?;
        }
    }
    read_into(node, "damping", &mut spec.damping);
    if let Some(a) = read_one(node, "armature") {
        spec.armature = a;
    }
    if let Some(a) = read_one(node, "actdim") {
        spec.actdim = a as i64;
    }
    if let Some(k) = keyword(node, "dyntype") {
        spec.dyntype = known(k, DYN).ok_or(None)?;
    }
    if let Some(k) = keyword(node, "gaintype") {
        let gaintype = known(k, GAIN).ok_or(None)?;
        // Another gain type clears the input signature a class gave (MuJoCo 4.0.0:
        // a class's `input="ff"` reaches a `<general>` that keeps the gain type, and
        // not one that sets `gaintype="affine"` or `"user"`).
        if gaintype != spec.gaintype {
            spec.ctrlspec = 0;
        }
        spec.gaintype = gaintype;
    }
    if let Some(k) = keyword(node, "biastype") {
        spec.biastype = known(k, BIAS).ok_or(None)?;
    }
    read_into(node, "dynprm", &mut spec.dynprm);
    read_into(node, "gainprm", &mut spec.gainprm);
    read_into(node, "biasprm", &mut spec.biasprm);
    if let Some(k) = keyword(node, "actearly") {
        spec.actearly = k == "true";
    }
    Ok(())
}

/// The transmission attributes, and the reader's refusals of those that do not go
/// with it.
fn transmission<'m>(spec: &mut Spec<'m>, node: &'m Node) -> Result<(), Option<&'static str>> {
    for (attr, trn) in [
        ("joint", Trn::Joint),
        ("jointinparent", Trn::JointInParent),
        ("tendon", Trn::Tendon),
        ("cranksite", Trn::SliderCrank),
        ("site", Trn::Site),
        ("body", Trn::Body),
    ] {
        if let Some(v) = own(node, attr) {
            spec.target = Some((attr, v));
            spec.trn = trn;
        }
    }
    let r1 = read_one(node, "cranklength").inspect(|c| spec.cranklength = *c).is_some();
    let r2 = own(node, "slidersite").is_some();
    spec.slidersite |= r2;
    if (r1 || r2) && !matches!(spec.trn, Trn::SliderCrank | Trn::Undefined) {
        return Err(Some(
            "cranklength and slidersite can only be used in slidercrank transmission",
        ));
    }
    let r3 = own(node, "refsite").is_some();
    spec.refsite |= r3;
    if r3 && !matches!(spec.trn, Trn::Site | Trn::Undefined) {
        return Err(Some("refsite can only be used with site transmission"));
    }
    Ok(())
}

/// `kv` and `dampratio` into `biasprm[2]` (`mjs_setToPosition` and the servos).
fn damping_of(spec: &mut Spec<'_>, node: &Node) -> Result<(), Option<&'static str>> {
    let (kv, dampratio) = (read_one(node, "kv"), read_one(node, "dampratio"));
    if kv.is_some() && dampratio.is_some() {
        return Err(Some("kv and dampratio cannot both be defined"));
    }
    if let Some(kv) = kv {
        if kv < 0.0 {
            return Err(Some("kv cannot be negative"));
        }
        spec.biasprm[2] = -kv;
    }
    if let Some(d) = dampratio {
        if d < 0.0 {
            return Err(Some("dampratio cannot be negative"));
        }
        spec.biasprm[2] = d;
    }
    Ok(())
}

/// `<position>` and `<intvelocity>` (`mjs_setToPosition`, `mjs_setToIntVelocity`).
fn position(
    spec: &mut Spec<'_>,
    node: &Node,
    intvelocity: bool,
) -> Result<(), Option<&'static str>> {
    let kp = read_one(node, "kp").unwrap_or(spec.gainprm[0]);
    let inheritrange = read_one(node, "inheritrange").unwrap_or(spec.inheritrange);
    spec.gainprm[0] = kp;
    spec.biasprm[1] = -kp;
    damping_of(spec, node)?;
    if let Some(t) = read_one(node, "timeconst") {
        if t < 0.0 {
            return Err(Some("timeconst cannot be negative"));
        }
        spec.dynprm[0] = t;
        spec.dyntype = if t == 0.0 { "none" } else { "filterexact" };
    }
    spec.inheritrange = inheritrange;
    // MuJoCo 4.0.0 refuses both given on the element (a class's ctrlrange gives way
    // to the element's inheritrange).
    let ctrl_too = inheritrange > 0.0
        && own(node, "inheritrange").is_some()
        && (spec.ctrlrange[0] != 0.0 || spec.ctrlrange[1] != 0.0)
        && own(node, "ctrlrange").is_some();
    if ctrl_too && !intvelocity {
        return Err(Some("ctrlrange and inheritrange cannot both be defined"));
    }
    (spec.gaintype, spec.biastype) = ("fixed", "affine");
    if intvelocity {
        spec.dyntype = "integrator";
        if inheritrange > 0.0
            && own(node, "inheritrange").is_some()
            && own(node, "actrange").is_some()
            && (spec.actrange[0] != 0.0 || spec.actrange[1] != 0.0)
        {
            return Err(Some("actrange and inheritrange cannot both be defined"));
        }
    }
    Ok(())
}

/// `<orientation>` (`mjs_setToOrientation`).
fn orientation(spec: &mut Spec<'_>, node: &Node) -> Result<(), Option<&'static str>> {
    let kp = read_one(node, "kp").unwrap_or(spec.gainprm[0]);
    if let Some(i) = input(node) {
        spec.ctrlspec = i.ok_or(None)?;
    }
    damping_of(spec, node)?;
    spec.gainprm[0] = kp;
    spec.biasprm[1] = -kp;
    (spec.gaintype, spec.biastype, spec.dyntype) = ("so3", "so3", "none");
    Ok(())
}

/// `<pid>` (`mjs_setToPID`): `ki`, `imax`, `slewmax` inherited only from a pid with
/// controller states.
fn pid(spec: &mut Spec<'_>, node: &Node) -> Result<(), Option<&'static str>> {
    let kp = read_one(node, "kp").unwrap_or(-spec.biasprm[1]);
    let stateful = if spec.dyntype == "pid" { 1.0 } else { 0.0 };
    let ki = read_one(node, "ki").unwrap_or(spec.gainprm[0] * stateful);
    let imax = read_one(node, "imax").unwrap_or(spec.dynprm[0] * stateful);
    let slewmax = read_one(node, "slewmax").unwrap_or(spec.dynprm[1] * stateful);
    if let Some(i) = input(node) {
        spec.ctrlspec = i.ok_or(None)?;
    }
    read_into(node, "posrange", &mut spec.ctrlrange);
    let inheritrange = read_one(node, "inheritrange").unwrap_or(spec.inheritrange);
    // MuJoCo's reader always passes ki, imax and slewmax.
    let (kv, dampratio) = (read_one(node, "kv"), read_one(node, "dampratio"));
    if kv.is_some() && dampratio.is_some() {
        return Err(Some("kv and dampratio cannot both be defined"));
    }
    spec.biasprm[1] = -kp;
    damping_of(spec, node)?;
    if slewmax < 0.0 {
        return Err(Some("slewmax cannot be negative"));
    }
    spec.gainprm[0] = ki;
    spec.dynprm[1] = slewmax;
    spec.dyntype = if ki != 0.0 || slewmax != 0.0 { "pid" } else { "none" };
    if ki != 0.0 {
        spec.dynprm[0] = imax;
    }
    spec.inheritrange = inheritrange;
    if inheritrange > 0.0
        && own(node, "inheritrange").is_some()
        && (own(node, "posrange").is_some() || own(node, "ctrlrange").is_some())
        && (spec.ctrlrange[0] != 0.0 || spec.ctrlrange[1] != 0.0)
    {
        return Err(Some("posrange and inheritrange cannot both be defined"));
    }
    (spec.gaintype, spec.biastype) = ("pid", "affine");
    Ok(())
}

/// `<damper>` (`mjs_setToDamper`): `kv` inherited from an affine gain.
fn damper(spec: &mut Spec<'_>, node: &Node) -> Result<(), Option<&'static str>> {
    let inherited = if spec.gaintype == "affine" { -spec.gainprm[2] } else { 0.0 };
    let kv = read_one(node, "kv").unwrap_or(inherited);
    spec.gainprm = [0.0; NPRM];
    spec.gainprm[2] = -kv;
    spec.ctrllimited = Limited::True;
    (spec.dyntype, spec.gaintype, spec.biastype) = ("none", "affine", "none");
    if kv < 0.0 {
        return Err(Some("damping coefficient cannot be negative"));
    }
    if spec.ctrlrange[0] < 0.0 || spec.ctrlrange[1] < 0.0 {
        return Err(Some("damper control range cannot be negative"));
    }
    Ok(())
}

/// `<cylinder>` (`mjs_setToCylinder`).
fn cylinder(spec: &mut Spec<'_>, node: &Node) -> Result<(), Option<&'static str>> {
    let timeconst = read_one(node, "timeconst").unwrap_or(spec.dynprm[0]);
    let mut bias = [spec.biasprm[0], spec.biasprm[1], spec.biasprm[2]];
    read_into(node, "bias", &mut bias);
    let mut area = read_one(node, "area").unwrap_or(spec.gainprm[0]);
    if let Some(d) = read_one(node, "diameter").filter(|d| *d >= 0.0) {
        area = std::f64::consts::PI / 4.0 * d * d;
    }
    spec.dynprm[0] = timeconst;
    spec.biasprm[..3].copy_from_slice(&bias);
    spec.gainprm[0] = area;
    (spec.dyntype, spec.gaintype, spec.biastype) = ("filter", "fixed", "affine");
    Ok(())
}

/// `<muscle>` (`mjs_setToMuscle`): MuJoCo's muscle defaults where the spec holds the
/// global ones, then the element's values (a negative one is "not given").
fn muscle(spec: &mut Spec<'_>, node: &Node) -> Result<(), Option<&'static str>> {
    let tausmooth = read_one(node, "tausmooth").unwrap_or(spec.dynprm[2]);
    let mut timeconst = [-1.0; 2];
    read_into(node, "timeconst", &mut timeconst);
    let mut range = [-1.0; 2];
    read_into(node, "range", &mut range);
    let given: Vec<f64> = ["force", "scale", "lmin", "lmax", "vmax", "fpmax", "fvmax"]
        .iter()
        .map(|a| read_one(node, a).unwrap_or(-1.0))
        .collect();
    let (d, g) = (&mut spec.dynprm, &mut spec.gainprm);
    if d[0] == 1.0 {
        d[0] = 0.01;
    }
    if d[1] == 0.0 {
        d[1] = 0.04;
    }
    if g[0] == 1.0 {
        g[0] = 0.75;
    }
    for (i, v) in [1.05, -1.0, 200.0, 0.5, 1.6, 1.5, 1.3, 1.2].into_iter().enumerate() {
        if g[i + 1] == 0.0 {
            g[i + 1] = v;
        }
    }
    if tausmooth < 0.0 {
        return Err(Some("muscle tausmooth cannot be negative"));
    }
    d[2] = tausmooth;
    for (i, t) in timeconst.into_iter().enumerate() {
        if t >= 0.0 {
            d[i] = t;
        }
    }
    for (i, r) in range.into_iter().chain(given).enumerate() {
        if r >= 0.0 {
            g[i] = r;
        }
    }
    spec.biasprm[..9].copy_from_slice(&spec.gainprm[..9]);
    (spec.dyntype, spec.gaintype, spec.biastype) = ("muscle", "muscle", "muscle");
    Ok(())
}

/// `<adhesion>` (`mjs_setToAdhesion`).
fn adhesion(spec: &mut Spec<'_>, node: &Node) -> Result<(), Option<&'static str>> {
    let gain = read_one(node, "gain").unwrap_or(spec.gainprm[0]);
    spec.gainprm[0] = gain;
    spec.ctrllimited = Limited::True;
    (spec.gaintype, spec.biastype) = ("fixed", "none");
    if gain < 0.0 {
        return Err(Some("adhesion gain cannot be negative"));
    }
    if spec.ctrlrange[0] < 0.0 || spec.ctrlrange[1] < 0.0 {
        return Err(Some("adhesion control range cannot be negative"));
    }
    Ok(())
}

/// `<dcmotor>` (`mjs_setToDCMotor`): its motor constant and resistance (given, or
/// derived from `nominal`), its controller gains and slew limit, over `spec`.
fn dcmotor(spec: &mut Spec<'_>, node: &Node) -> Result<(), Option<&'static str>> {
    // Values a class's dcmotor gives, else zero.
    let inherited = spec.gaintype == "dcmotor";
    let from = |x: f64| if inherited { x } else { 0.0 };
    let mut motorconst = [from(spec.gainprm[1]), 0.0];
    let mut resistance = from(spec.gainprm[0]);
    let mut nominal = [0.0; 3];
    let mut inductance = [0.0, from(spec.dynprm[0])];
    let mut controller = [
        from(spec.gainprm[4]),
        from(spec.gainprm[5]),
        from(spec.gainprm[6]),
        from(spec.dynprm[7]),
        from(spec.dynprm[8]),
        from(spec.gainprm[7]),
    ];
    let mut ctrlspec = if inherited { spec.ctrlspec } else { 0 };
    read_into(node, "motorconst", &mut motorconst);
    if let Some(r) = read_one(node, "resistance") {
        resistance = r;
    }
    read_into(node, "nominal", &mut nominal);
    read_into(node, "inductance", &mut inductance);
    read_into(node, "controller", &mut controller);
    if let Some(i) = input(node) {
        ctrlspec = i.ok_or(None)?;
    }
    // Checked with MuJoCo 4.0.0 (not in the source it was read from): a negative
    // motor constant is refused first.
    let [kt, mut ke] = motorconst;
    if kt < 0.0 || ke < 0.0 {
        return Err(Some("DC motor: motor constants must be non-negative"));
    }
    let mut r = resistance;
    let [vn, tau0, omega0] = nominal;
    if vn > 0.0 && ke <= 0.0 && omega0 > 0.0 {
        let b = spec.damping[0];
        ke = if b > 0.0 && r > 0.0 {
            let disc = vn * vn - 4.0 * r * b * omega0 * omega0;
            if disc > 0.0 { (vn + disc.sqrt()) / (2.0 * omega0) } else { vn / omega0 }
        } else if b > 0.0 && tau0 > 0.0 {
            let exact = vn / omega0 - vn * b / tau0;
            if exact > 0.0 { exact } else { vn / omega0 }
        } else {
            vn / omega0
        };
    }
    let k = if kt > 0.0 && ke > 0.0 {
        (kt * ke).sqrt()
    } else if kt > 0.0 {
        kt
    } else {
        ke
    };
    if r == 0.0 && vn > 0.0 && tau0 > 0.0 && k > 0.0 {
        r = k * vn / tau0;
    }
    // Checked with MuJoCo 4.0.0: a passive motor (`input="none"`) needs no motor
    // constant.
    if k <= 0.0 && ctrlspec != INPUT_NONE {
        return Err(Some("DC motor: motor constant K must be positive"));
    }
    if r <= 0.0 {
        return Err(Some("DC motor: resistance R must be positive"));
    }
    (spec.dyntype, spec.gaintype, spec.biastype) = ("dcmotor", "dcmotor", "dcmotor");
    spec.gainprm[0] = r;
    spec.gainprm[1] = k;
    spec.gainprm[4] = controller[0];
    spec.gainprm[5] = controller[1];
    spec.gainprm[6] = controller[2];
    spec.dynprm[7] = controller[3];
    spec.dynprm[8] = controller[4];
    if inductance[0] < 0.0 {
        return Err(Some("DC motor: inductance must be non-negative"));
    }
    if inductance[1] < 0.0 {
        return Err(Some("DC motor: electrical time constant must be non-negative"));
    }
    // The thermal and friction models are not emulated: the checks judging a
    // dcmotor read none of what they set.
    spec.ctrlspec = ctrlspec;
    spec.actearly = true;
    Ok(())
}
