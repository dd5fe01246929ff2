//! Saving a composed model as a scene that references its parts, the way MuJoCo 4.0
//! composes models itself: `<asset><model name="robot" file="robot.xml"/></asset>`
//! and, at the attachment frame, `<attach model="robot" prefix="robot/"/>`.
//!
//! # The transformation ([`Model::to_scene`])
//! A composed model becomes a parent model plus one part per distinct attached model
//! value (values that are `ptr_eq` share one part), recursively; nested attachments
//! nest the same way (a part is itself a parent of its own attachments). What each
//! attachment frame, the parent's assets and its settings become is the manual's
//! ("Saved", under [Scenes](crate::guide#scenes)); [`transform`] makes a parent,
//! [`frame_as_body`] a frame's element.
//!
//! Every part is written by one function, [`write_part`]; the files a part names
//! (meshes, textures, the part files of its own attachments) are its model file's
//! companions, so the scene's root model names every file of the scene and
//! [`Model::save_scene`] is [`Model::export`] of it. The lossless save of a model
//! read from a file ([`Model::save`], `xml::save::scene`) writes its parts built in
//! code with the same [`Model::to_scene`] and [`write_part`].
//!
//! What MuJoCo compiles differently from `to_xml_string()` (each file's own compiler
//! settings, the keys of attached models, the order of attached sections, automatic
//! names, a class named `main` below a part's root class), with the figures, is the
//! manual's ([Scenes](crate::guide#scenes)).

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use smol_str::SmolStr;

use crate::error::{ExportError, WriteError};
use crate::model::naming::Written;
use crate::model::settings;
use crate::model::tree::{Attr, ElementId, Node};
use crate::model::{Index, Model, Walk};
use crate::schema::{ElementKind, Namespace, Role};
use crate::value::{FileAsset, Reference, Value};
use crate::xml::{WriteOptions, frame_keeps_bodies_top_level};

pub(crate) mod reopen;
#[cfg(test)]
mod tests;

/// A composed model as a scene: a root model whose attachments are MuJoCo
/// `<attach>`es of asset `<model>`s, and the parts those name ([`Model::to_scene`];
/// the [scene rules](crate::guide#scenes)).
#[derive(Clone, Debug)]
pub struct Scene {
    root: Model,
    parts: Vec<ScenePart>,
}

/// One part of a [`Scene`]: an attached model value, transformed as the scene's root
/// is (its own attachments are `<attach>`es in turn), and the file name the scene
/// gives it.
#[derive(Clone, Debug)]
pub struct ScenePart {
    file_name: String,
    model: Model,
}

impl Scene {
    /// The root model: the composed model's own content, its merged settings, an
    /// asset `<model>` per distinct attached model and an `<attach>` per attachment.
    ///
    /// Time: O(1).
    pub fn root(&self) -> &Model {
        &self.root
    }

    /// Every part, each distinct attached model value once (at any depth), in the
    /// order they are first met: the root's attached values in document order, then
    /// those attached to each of them, and so on.
    ///
    /// Time: O(1).
    pub fn parts(&self) -> &[ScenePart] {
        &self.parts
    }
}

impl ScenePart {
    /// The part's file name, relative to the scene's folder (`robot.xml`).
    ///
    /// Time: O(1).
    pub fn file_name(&self) -> &str {
        &self.file_name
    }

    /// The part, transformed: its own attachments are `<attach>`es of its parts.
    ///
    /// Time: O(1).
    pub fn model(&self) -> &Model {
        &self.model
    }
}

/// Where [`Model::save_scene`] wrote a scene.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SavedScene {
    path: PathBuf,
    parts: Vec<PathBuf>,
}

impl SavedScene {
    /// The scene's own file (`dir/scene.xml`): the one to open.
    ///
    /// Time: O(1).
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The part files, in the order of [`Scene::parts`].
    ///
    /// Time: O(1).
    pub fn parts(&self) -> &[PathBuf] {
        &self.parts
    }
}

/// The options every part is written with: the default ones (file names with their
/// hash, so that the files of all parts share one folder without clashes).
pub(crate) fn part_options() -> WriteOptions {
    WriteOptions::default()
}

/// Writes one part of a scene (the root or an attached model, transformed): the one
/// place that decides how parts are written.
///
/// Time: as [`Model::to_xml_string_with`].
pub(crate) fn write_part(part: &Model) -> Result<String, WriteError> {
    part.to_xml_string_with(&part_options())
}

impl Model {
    /// This model as a scene that references its parts (see [`Scene`]): the
    /// transformation [`Model::save_scene`] writes. `file_name` is the name the
    /// root's file will have (no part is given it).
    ///
    /// Time: O(N · log n + L) for the `N` elements of the distinct model values of the
    /// composition (each transformed and written once, however often it is
    /// attached) written as `L` bytes, plus O(a · depth · log n) to fold the merged
    /// settings of each.
    ///
    /// # Errors
    /// [`WriteError::Conflict`] when the merged settings of a model cannot be folded
    /// (no edit makes such a model); otherwise what writing a part
    /// ([`Model::to_xml_string_with`]) or listing its files ([`Model::assets`])
    /// reports.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, element};
    /// let mut robot = Model::new("robot");
    /// robot.add_mut(&robot.worldbody(), element!("body", name = "torso"))?;
    /// let mut arena = Model::new("arena");
    /// let a = arena.attach_mut(&arena.worldbody(), &robot)?;
    /// arena.attach_mut(&arena.worldbody(), &robot)?;
    /// arena.add_mut(a.frame(), element!("joint", type = "slide"))?;
    /// let scene = arena.to_scene("scene.xml")?;
    /// let parts: Vec<_> = scene.parts().iter().map(|p| p.file_name()).collect();
    /// assert_eq!(parts, ["robot.xml"]); // one value attached twice: one file
    /// let xml = scene.root().to_xml_string()?;
    /// assert!(xml.contains(r#"<model name="robot" file="robot.xml"/>"#));
    /// assert!(xml.contains(r#"<body name="robot/">"#));
    /// assert!(xml.contains(r#"<joint name="robot/" class="/" type="slide"/>"#));
    /// assert!(xml.contains(r#"<attach model="robot" prefix="robot_1/"/>"#));
    /// # Ok::<(), mjcf::Error>(())
    /// ```
    pub fn to_scene(&self, file_name: &str) -> Result<Scene, WriteError> {
        let (order, children) = distinct_models(self);
        // File names: the root's is reserved; each part's after its model's name.
        let mut taken: Vec<String> = vec![file_name.to_ascii_lowercase()];
        let mut names: Vec<String> = Vec::with_capacity(order.len());
        for m in order.iter().skip(1) {
            let stem = file_stem(m.name());
            let mut k = 0;
            let name = loop {
                let candidate =
                    if k == 0 { format!("{stem}.xml") } else { format!("{stem}_{k}.xml") };
                if !taken.contains(&candidate.to_ascii_lowercase()) {
                    break candidate;
                }
                k += 1;
            };
            taken.push(name.to_ascii_lowercase());
            names.push(name);
        }
        // Children before parents (post-order over the values, which attach one
        // another without cycles): a part's asset `<model>` holds its children's text.
        let mut files: Vec<Option<FileAsset>> = vec![None; order.len()];
        let mut parts: Vec<Option<Model>> = vec![None; order.len()];
        let mut stack: Vec<(usize, bool)> = vec![(0, false)];
        while let Some((i, ready)) = stack.pop() {
            if parts[i].is_some() {
                continue;
            }
            if !ready {
                stack.push((i, true));
                stack.extend(children[i].iter().map(|&c| (c, false)));
                continue;
            }
            let mut own: Vec<(&Model, FileAsset)> = Vec::with_capacity(children[i].len());
            for &c in &children[i] {
                // Every child was made before its parent.
                let file = files[c].clone().ok_or_else(|| {
                    WriteError::Conflict(format!("the part of '{}' is missing", order[c].name()))
                })?;
                own.push((order[c], file));
            }
            let part = transform(order[i], &own)?;
            if i > 0 {
                let text = write_part(&part)?;
                let companions: Vec<(SmolStr, FileAsset)> = part
                    .assets(&part_options())?
                    .into_iter()
                    .map(|(name, file)| (SmolStr::from(name), file))
                    .collect();
                let name = &names[i - 1];
                let stem = name.strip_suffix(".xml").unwrap_or(name);
                files[i] = Some(
                    FileAsset::with_fixed_name(stem, ".xml", text.into_bytes())
                        .with_companions(companions),
                );
            }
            parts[i] = Some(part);
        }
        let mut parts = parts.into_iter().flatten();
        let Some(root) = parts.next() else {
            return Err(WriteError::Conflict("the scene has no root".into()));
        };
        let parts =
            parts.zip(names).map(|(model, file_name)| ScenePart { file_name, model }).collect();
        Ok(Scene { root, parts })
    }

    /// Saves this model as a scene that references its parts ([`Model::to_scene`]):
    /// `dir/file_name` holds this model's own content with each attachment as
    /// MuJoCo's `<attach>` of an asset `<model>`, each distinct attached model value
    /// is a file of its own beside it (`robot.xml`; attachments inside it are
    /// `<attach>`es in turn), and the meshes, textures and other files every part
    /// names are written there too, as [`Model::export`] writes them (each once,
    /// named with its hash). MuJoCo loads the scene from `dir/file_name`
    /// (`MjModel.from_xml_path`), and [`Model::from_path`] reads it back composed:
    /// the attachments are attachments again.
    ///
    /// This is the way to write a composed model that was not read from a file: every
    /// part is written with the plain writer. A model read from a file (a reopened
    /// scene, or a file with attachments added in code) saves with [`Model::save`] or
    /// [`Model::save_as`] instead, which keep its text and its parts' files as they
    /// were read and write the parts built in code as this function does (the same
    /// [`Model::to_scene`] and part writer).
    ///
    /// Writes are atomic, as [`Model::export`]'s: every file is written under a
    /// temporary name and renamed into place, the scene's own file last; nothing is
    /// written before every part was written to text and every name checked.
    ///
    /// What MuJoCo compiles differently from the composed text
    /// ([`Model::to_xml_string`]: each file's own compiler settings, the layout of
    /// attached models' keys, attached sections in document order) and what reopens
    /// as an attachment are the [scene rules](crate::guide#scenes).
    ///
    /// Time: as [`Model::to_scene`], plus writing every file (as [`Model::export`]).
    ///
    /// # Errors
    /// As [`Model::to_scene`] (as [`ExportError::Write`]) and [`Model::export`]:
    /// nothing is written when the scene cannot be made or a name is not a plain file
    /// name; [`ExportError::Io`] when a folder or file cannot be written.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut robot = Model::new("robot");
    /// robot.add_mut(&robot.worldbody(), element!("body", name = "torso"))?;
    /// let mut arena = Model::new("arena");
    /// let spawn = arena.add_mut(&arena.worldbody(), element!("site", name = "spawn", pos = [1, 0, 0]))?;
    /// arena.attach_mut(&spawn, &robot)?;
    /// let dir = std::env::temp_dir().join(format!("mjcf-scene-doc-{}", std::process::id()));
    /// let saved = arena.save_scene(&dir, "scene.xml")?;
    /// assert_eq!(saved.parts(), [dir.join("robot.xml")]);
    /// let back = Model::from_path(saved.path())?;
    /// assert_eq!(back.scopes().collect::<Vec<_>>(), ["robot"]); // composed again
    /// assert_eq!(back.to_xml_string()?, arena.to_xml_string()?);
    /// let back = back.detach("robot")?;
    /// assert!(back.find(Namespace::Body, "robot/torso").is_none());
    /// # std::fs::remove_dir_all(&dir).unwrap();
    /// # Ok::<(), mjcf::Error>(())
    /// ```
    pub fn save_scene(
        &self,
        dir: impl AsRef<Path>,
        file_name: &str,
    ) -> Result<SavedScene, ExportError> {
        let dir = dir.as_ref();
        let scene = self.to_scene(file_name)?;
        let path = scene.root.export(dir, file_name, &part_options())?;
        let parts = scene.parts.iter().map(|p| dir.join(&p.file_name)).collect();
        Ok(SavedScene { path, parts })
    }
}

/// Every distinct model value of the composition (`model` first), each once, in the
/// order first met (a model's attachments in document order, then theirs), and for
/// each, the distinct values attached to it (their positions in that list, in attach
/// order).
fn distinct_models(model: &Model) -> (Vec<&Model>, Vec<Vec<usize>>) {
    let mut values = Values { order: vec![model], by_root: HashMap::new() };
    values.by_root.entry(model.root.id()).or_default().push(0);
    let mut stack: Vec<&Model> = vec![model];
    while let Some(m) = stack.pop() {
        let mut found = Vec::new();
        for node in m.root.descendants() {
            if let Some(a) = node.attached() {
                if values.position(&a.model).is_none() {
                    values.add(&a.model);
                    found.push(&a.model);
                }
            }
        }
        stack.extend(found.into_iter().rev());
    }
    let children = values
        .order
        .iter()
        .map(|m| {
            let mut own: Vec<usize> = Vec::new();
            for i in settings::attachments(m).into_iter().filter_map(|c| values.position(c)) {
                if !own.contains(&i) {
                    own.push(i);
                }
            }
            own
        })
        .collect();
    (values.order, children)
}

/// Distinct model values, told apart by their root's id, then by `ptr_eq`.
struct Values<'a> {
    order: Vec<&'a Model>,
    by_root: HashMap<ElementId, Vec<usize>>,
}

impl<'a> Values<'a> {
    fn position(&self, m: &Model) -> Option<usize> {
        self.by_root.get(&m.root.id())?.iter().copied().find(|&i| self.order[i].ptr_eq(m))
    }

    fn add(&mut self, m: &'a Model) {
        self.by_root.entry(m.root.id()).or_default().push(self.order.len());
        self.order.push(m);
    }
}

/// A file stem for a model's name: its characters that are safe in a file name on
/// every common file system (ASCII letters, digits, `_`, `-`, `.` not leading),
/// others as `_`, at most 200 bytes; `model` if nothing is left.
pub(crate) fn file_stem(name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.') { c } else { '_' })
        .take(200)
        .collect();
    while s.starts_with('.') {
        s.remove(0);
    }
    if s.is_empty() { "model".to_string() } else { s }
}

/// What a frame of `model` becomes in the scene: its joints' names as the composed
/// writer writes them (frame joints by id; automatic names left out: the part's writer
/// gives an unnamed joint the same one).
pub(crate) fn frame_joint_names(model: &Model) -> HashMap<ElementId, String> {
    let walk = Walk::new(model);
    let mut out = HashMap::new();
    for frame in model.root.descendants().filter(|n| n.attached().is_some()) {
        for j in frame.children().iter().filter(|c| c.kind().namespace().is_some()) {
            if let Some(w @ (Written::Frame(_) | Written::FrameJoint(..))) =
                walk.insts.name_of_id(0, j.id())
            {
                out.insert(j.id(), w.to_string_in(""));
            }
        }
    }
    out
}

/// `model` transformed into a scene part: its merged settings as its own, an asset
/// `<model>` per distinct attached model (`children`: each with its file), and each
/// attachment frame a body (or MuJoCo `<frame>`) holding an `<attach>`.
fn transform(model: &Model, children: &[(&Model, FileAsset)]) -> Result<Model, WriteError> {
    // The asset `<model>`s, named after their files, each free in this model.
    let model_kind = ElementKind::ASSET.child_of_role(Role::AssetModel);
    let mut assets: Vec<Node> = Vec::new();
    let mut asset_of: Vec<(&Model, ElementId)> = Vec::new();
    let mut used: Vec<SmolStr> = Vec::new();
    if let Some(kind) = model_kind {
        for (child, file) in children {
            let mut name = SmolStr::from(file.stem());
            let mut k = 0;
            while used.contains(&name)
                || model.index.names.contains_key(&(Namespace::Model, name.clone()))
            {
                k += 1;
                name = smol_str::format_smolstr!("{}_{k}", file.stem());
            }
            used.push(name.clone());
            let id = ElementId::fresh();
            let attrs = attrs_of(
                kind,
                [("name", Value::Identifier(name)), ("file", Value::File(file.clone()))],
            );
            assets.push(Node::new(id, kind, attrs, Default::default()));
            asset_of.push((child, id));
        }
    }
    /// The whole scene written anew.
    struct Anew<'a>(&'a [Node]);
    impl Spelling for Anew<'_> {
        fn assets(&mut self, section: &Node) -> Node {
            if self.0.is_empty() {
                return section.clone();
            }
            let mut own = section.children().clone();
            for a in self.0 {
                own.push_back(a.clone());
            }
            section.with_children(own)
        }
    }
    let root = spell(model, &asset_of, &mut Anew(&assets)).map_err(|e| {
        WriteError::Conflict(match e {
            SpellError::Settings(k) => k,
            SpellError::NoPart => format!("a model attached to '{}' has no part", model.name()),
        })
    })?;
    let mut index = Index::default();
    index.insert_subtree(None, &root, 0).map_err(|d| {
        WriteError::Conflict(format!(
            "the scene's name '{}' ({}) is taken",
            d.name,
            d.namespace.as_str()
        ))
    })?;
    Ok(Model::from_parts(root, index, crate::files::FileContext::clone(&model.files)))
}

/// How a walk of [`spell`] spells a composed model as a scene: [`Model::save_scene`]
/// writes everything anew; the lossless save keeps the nodes it read where nothing
/// changed.
pub(crate) trait Spelling {
    /// The attachment frame `frame`, to be written as `written` (the body, or MuJoCo
    /// `<frame>`, holding its `<attach>`): what is written (`None`: it cannot be).
    fn frame(&mut self, frame: &Node, written: Node) -> Option<Node> {
        let _ = frame;
        Some(written)
    }

    /// The `<asset>` section with the scene's asset `<model>`s.
    fn assets(&mut self, section: &Node) -> Node;

    /// `n` with its children spelled as `kids`.
    fn node(&mut self, n: &Node, kids: Vec<Node>) -> Node {
        if kids.iter().zip(n.children().iter()).all(|(a, b)| a.ptr_eq(b)) {
            return n.clone();
        }
        n.with_children(kids.into_iter().collect())
    }
}

/// Why [`spell`] failed.
pub(crate) enum SpellError {
    /// The attached models' settings cannot be merged (what conflicts).
    Settings(String),
    /// An attached model has no asset `<model>` (no part).
    NoPart,
}

/// `model` spelled as a scene, the one walk of both saves: every attachment frame a
/// body (or MuJoCo `<frame>`) holding `<attach model="M" prefix="scope/"/>`, `M` its
/// model's asset in `asset_of`; the global settings sections the merged ones; the
/// `<asset>` section as `how` gives it.
///
/// Time: O(n) for the `n` elements of the model, plus `how`'s.
pub(crate) fn spell(
    model: &Model,
    asset_of: &[(&Model, ElementId)],
    how: &mut impl Spelling,
) -> Result<Node, SpellError> {
    let merged = settings::merged(model).map_err(|k| SpellError::Settings(k.to_string()))?;
    let joint_names = frame_joint_names(model);
    let world: HashSet<ElementId> = world_level(model).into_iter().collect();
    let mut missing = false;
    let root = model.root.rebuild(|n, children| {
        let parent_world = world.contains(&n.id());
        let mut kids: Vec<Node> = Vec::with_capacity(children.len());
        for new in children.iter() {
            if new.attached().is_none() {
                kids.push(new.clone());
                continue;
            }
            let written = frame_as_body(new, n.kind(), parent_world, &joint_names, asset_of);
            kids.push(written.and_then(|w| how.frame(new, w)).unwrap_or_else(|| {
                missing = true;
                new.clone()
            }));
        }
        if n.kind() == ElementKind::ROOT {
            for c in kids.iter_mut() {
                if settings::is_settings_section(c.kind()) {
                    if let Some(m) = merged.iter().find(|m| m.kind() == c.kind()) {
                        *c = m.clone();
                    }
                } else if c.kind() == ElementKind::ASSET {
                    *c = how.assets(c);
                }
            }
        }
        how.node(n, kids)
    });
    if missing {
        return Err(SpellError::NoPart);
    }
    Ok(root)
}

/// The world-level containers of `model`: the worldbody and the MuJoCo `<frame>`s in
/// it (whose bodies are top-level bodies for MuJoCo).
pub(crate) fn world_level(model: &Model) -> Vec<ElementId> {
    let mut out: Vec<ElementId> = Vec::new();
    if let Some(wb) = model.root.child_of_kind(ElementKind::WORLDBODY) {
        let mut stack = vec![wb];
        while let Some(n) = stack.pop() {
            out.push(n.id());
            stack.extend(
                n.children().iter().filter(|c| c.kind().is(Role::Frame) && c.attached().is_none()),
            );
        }
    }
    out
}

/// The attachment frame `frame` (a child of an element of kind `parent`) as a scene
/// body named `scope/`, with its pose, its joints named as written and an `<attach>`
/// of its model's asset; a MuJoCo `<frame>` where the composed writer writes one.
/// `None` if its model has no asset in `asset_of`.
pub(crate) fn frame_as_body(
    frame: &Node,
    parent: ElementKind,
    parent_world: bool,
    joint_names: &HashMap<ElementId, String>,
    asset_of: &[(&Model, ElementId)],
) -> Option<Node> {
    let a = frame.attached()?;
    let asset = asset_of.iter().find(|(m, _)| m.ptr_eq(&a.model))?.1;
    let name = Value::Identifier(smol_str::format_smolstr!("{}/", a.scope));
    let kind = if kind_is_frame(frame, parent, parent_world) {
        parent.child_of_role(Role::Frame)?
    } else {
        frame.kind()
    };
    let attach = kind.child_of_role(Role::Attach)?;
    let mut attrs: Vec<Attr> = frame
        .attrs()
        .iter()
        .filter_map(|(i, v)| {
            let n = frame.kind().attr(*i as usize).name;
            Some((kind.attr_index(n)? as u16, v.clone()))
        })
        .collect();
    if let Some(i) = kind.identifier() {
        attrs.retain(|(k, _)| *k as usize != i);
        attrs.push((i as u16, name));
    }
    let mut children: crate::seq::Seq<Node> = frame
        .children()
        .iter()
        .map(|c| match (joint_names.get(&c.id()), c.kind().identifier()) {
            (Some(n), Some(i)) => {
                let mut attrs = c.attrs().to_vec();
                attrs.retain(|(k, _)| *k as usize != i);
                attrs.push((i as u16, Value::Identifier(n.into())));
                c.with_attrs(attrs)
            }
            _ => c.clone(),
        })
        .collect();
    let attach_attrs = attrs_of(
        attach,
        [
            ("model", Value::Reference(Reference::Element(asset))),
            ("prefix", Value::String(smol_str::format_smolstr!("{}/", a.scope))),
        ],
    );
    children.push_back(Node::new(ElementId::fresh(), attach, attach_attrs, Default::default()));
    Some(Node::new(frame.id(), kind, attrs, children))
}

/// Whether the attachment frame `frame` (a child of an element of kind `parent`, in
/// the world or not) is written as MuJoCo's `<frame>` (decision D10), as the composed
/// writer writes it.
fn kind_is_frame(frame: &Node, parent: ElementKind, parent_world: bool) -> bool {
    parent_world
        && parent.child_of_role(Role::Frame).is_some()
        && frame_keeps_bodies_top_level(frame)
}

/// The attributes `values` of an element of `kind` (those it has).
pub(crate) fn attrs_of<const N: usize>(kind: ElementKind, values: [(&str, Value); N]) -> Vec<Attr> {
    values.into_iter().filter_map(|(n, v)| Some((kind.attr_index(n)? as u16, v))).collect()
}
