//! Scanning MJCF text for what it names without reading it as a model: the files its
//! elements name (what an asset `<model>` file brings with it, `model::build`; the reader's
//! own reading of a file is `xml::read`, which this scan follows) and its
//! root's `model` attribute. Elements are told apart by the schema, as the reader tells
//! them apart (the element kind reached from the root, its attributes' types), so that
//! the scan finds exactly the files and folder settings the reader would read.

use smol_str::SmolStr;

use crate::schema::{AttrType, ElementKind, PathNamespace, Role};

/// The tag of MuJoCo's `<include>`, which is not an element of the schema: the
/// reader puts the file's content in its place.
pub(crate) const INCLUDE: &str = "include";

/// The folder settings of a model's compiler, which decide where files are read from.
#[derive(Clone, Debug, Default)]
pub(crate) struct Basepaths {
    pub(crate) mesh: Option<SmolStr>,
    pub(crate) texture: Option<SmolStr>,
    pub(crate) asset: Option<SmolStr>,
}

impl Basepaths {
    pub(crate) fn for_namespace(&self, ns: Option<PathNamespace>) -> Option<&str> {
        let own = match ns {
            Some(PathNamespace::Mesh) => self.mesh.as_deref(),
            Some(PathNamespace::Texture) => self.texture.as_deref(),
            Some(PathNamespace::Asset) => self.asset.as_deref(),
            None => return None,
        };
        match ns {
            Some(PathNamespace::Mesh | PathNamespace::Texture) => own.or(self.asset.as_deref()),
            _ => own,
        }
    }

    /// Records a `compiler` folder setting.
    pub(crate) fn set(&mut self, ns: Option<PathNamespace>, value: Option<SmolStr>) {
        match ns {
            Some(PathNamespace::Mesh) => self.mesh = value,
            Some(PathNamespace::Texture) => self.texture = value,
            Some(PathNamespace::Asset) => self.asset = value,
            None => {}
        }
    }
}

/// A file that MJCF text names.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct NamedFile {
    /// The path as written.
    pub(crate) file: String,
    /// The compiler's folder setting that applies to it (the last one the text sets,
    /// as MuJoCo's compiler settings apply to every file), if any.
    pub(crate) folder: Option<SmolStr>,
    /// For MJCF that names files in turn: the element kind its root's content is read
    /// as (the root for an asset `<model>` file, the element holding an `<include>` for
    /// an included file).
    pub(crate) names_files: Option<ElementKind>,
    /// The name of the element naming it, for an asset `<model>` (which
    /// `<attach model=…>` refers to).
    pub(crate) model: Option<String>,
}

/// The files that MJCF `text`, whose root's content is read as the element kind
/// `root`, names, in document order (a path named again is listed again): every file
/// attribute of every element the schema knows at its place (of an element it does not
/// know, none: the reader refuses it), and every `<include>`. Content after malformed
/// XML is not scanned (reading the file reports it).
///
/// Time: O(length of `text`).
pub(crate) fn named_files(text: &str, root: ElementKind) -> Vec<NamedFile> {
    use quick_xml::events::Event;
    // In document order, each with the namespace of its folder: the folders apply
    // once the whole text is seen.
    let mut found: Vec<(NamedFile, Option<PathNamespace>)> = Vec::new();
    let named =
        |file: String, names_files, model| NamedFile { file, folder: None, names_files, model };
    let mut folders = Basepaths::default();
    // The kinds of the open elements (`None`: not read, such as an include's content).
    let mut open: Vec<Option<ElementKind>> = Vec::new();
    let mut xml = quick_xml::Reader::from_str(text);
    loop {
        let (tag, empty) = match xml.read_event() {
            Ok(Event::Start(t)) => (t, false),
            Ok(Event::Empty(t)) => (t, true),
            Ok(Event::End(_)) => {
                open.pop();
                continue;
            }
            Ok(Event::Eof) | Err(_) => break,
            Ok(_) => continue,
        };
        let qname = tag.name();
        let name: &str = qname.as_ref();
        let values = || {
            tag.attributes().flatten().filter_map(|a| {
                let v = a.normalized_value(quick_xml::XmlVersion::default()).ok()?;
                let key: &str = a.key.as_ref();
                Some((key.to_string(), v.into_owned()))
            })
        };
        let kind = match open.last() {
            None => Some(root),
            Some(&parent) if name == INCLUDE => {
                // Its content is not read; the file it names is, in the parent's place.
                let file = values().filter(|(k, v)| k == "file" && !v.is_empty()).last();
                if let (Some(parent), Some((_, file))) = (parent, file) {
                    found.push((named(file, Some(parent), None), None));
                }
                None
            }
            Some(&parent) => parent.and_then(|p| p.child(name)),
        };
        if let (Some(kind), false) = (kind, open.is_empty()) {
            let ident = kind.identifier();
            let model = kind.is(Role::AssetModel).then(|| {
                values().find(|(k, _)| kind.attr_index(k).is_some() && kind.attr_index(k) == ident)
            });
            let model = model.flatten().map(|(_, v)| v);
            for (key, value) in values() {
                let Some(i) = kind.attr_index(&key) else { continue };
                match kind.attr(i).ty {
                    AttrType::File { path_namespace } if !value.is_empty() => {
                        let names = kind.is(Role::AssetModel).then_some(ElementKind::ROOT);
                        found.push((named(value, names, model.clone()), path_namespace));
                    }
                    AttrType::Basepath { path_namespace } => {
                        let value = Some(SmolStr::from(value)).filter(|v| !v.is_empty());
                        folders.set(path_namespace, value);
                    }
                    _ => {}
                }
            }
        }
        if !empty {
            open.push(kind);
        }
    }
    found
        .into_iter()
        .map(|(named, ns)| NamedFile {
            folder: folders.for_namespace(ns).map(SmolStr::from),
            ..named
        })
        .collect()
}

/// The `model` attribute of the root element of MJCF `contents`, if it has a
/// non-empty one (and the contents are well-formed up to it).
///
/// Time: O(length of the text up to the root's start tag).
pub(crate) fn model_name(contents: &[u8]) -> Option<SmolStr> {
    use quick_xml::events::Event;
    let mut xml = quick_xml::Reader::from_reader(contents);
    let mut buf = Vec::new();
    loop {
        match xml.read_event_into(&mut buf).ok()? {
            Event::Start(t) | Event::Empty(t) => {
                let a = t.try_get_attribute("model").ok()??;
                let v = a.normalized_value(quick_xml::XmlVersion::default()).ok()?;
                return (!v.is_empty()).then(|| SmolStr::from(v.as_ref()));
            }
            Event::Eof => return None,
            _ => buf.clear(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A named file as (path, folder, tag of the kind it is read as).
    type Named = (String, Option<String>, Option<&'static str>);

    fn files(text: &str, root: ElementKind) -> Vec<Named> {
        named_files(text, root)
            .into_iter()
            .map(|n| (n.file, n.folder.map(|f| f.to_string()), n.names_files.map(|k| k.tag())))
            .collect()
    }

    fn named(file: &str, folder: Option<&str>, read_as: Option<&'static str>) -> Named {
        (file.to_string(), folder.map(str::to_string), read_as)
    }

    /// Every file attribute the schema types as a file, with the folder its type
    /// names (the last setting in the text, `assetdir` as the fallback of both): a
    /// cube map's six side files too, which a scan of `file` attributes missed.
    #[test]
    fn every_file_attribute_is_named_with_its_folder() {
        let text = r#"<mujoco><compiler meshdir="m1" assetdir="a"/><asset>
            <mesh file="x.stl"/><hfield file="h.png"/><skin file="s.skn"/>
            <texture type="cube" fileright="r.png" fileleft="l.png" fileup="u.png" filedown="d.png" filefront="f.png" fileback="b.png"/>
            <model name="robot" file="robot.xml"/></asset><compiler meshdir="m2"/></mujoco>"#;
        let mut want = vec![named("x.stl", Some("m2"), None), named("h.png", Some("m2"), None)];
        want.push(named("s.skn", Some("m2"), None));
        for side in ["r", "l", "u", "d", "f", "b"] {
            want.push(named(&format!("{side}.png"), Some("a"), None));
        }
        want.push(named("robot.xml", None, Some("mujoco")));
        assert_eq!(files(text, ElementKind::ROOT), want);
    }

    /// An `<include>` names its file, read as the content of the element holding it;
    /// an element the schema does not know there names nothing, and neither does an
    /// include's content nor anything after malformed XML.
    #[test]
    fn includes_name_their_file_in_place_unknown_elements_nothing() {
        let text = r#"<mujoco><asset><include file="meshes.xml"><mesh file="no.stl"/></include></asset>
            <bogus><mesh file="no2.stl"/></bogus><worldbody><mesh file="no3.stl"/></worldbody>
            <asset><mesh file="yes.stl"/></asset></worldbody><asset><mesh file="after.stl"/></asset></mujoco>"#;
        let want = [named("meshes.xml", None, Some("asset")), named("yes.stl", None, None)];
        assert_eq!(files(text, ElementKind::ROOT), want);
        // Read as an asset section's content (an included file): its meshes are named.
        let asset = ElementKind::ASSET;
        let text = r#"<mujoco><mesh file="a.stl"/></mujoco>"#;
        assert_eq!(files(text, asset), [named("a.stl", None, None)]);
    }

    /// An asset `<model>`'s file is named with the model's name (what `<attach
    /// model=…>` refers to); other files, and a model without a name, with none.
    #[test]
    fn asset_models_name_their_file_with_their_name() {
        let text = r#"<mujoco><asset><model name="robot" file="r.xml"/><model file="n.xml"/>
            <mesh name="robot" file="m.stl"/></asset></mujoco>"#;
        let models: Vec<_> =
            named_files(text, ElementKind::ROOT).into_iter().map(|n| (n.file, n.model)).collect();
        let want = [("r.xml", Some("robot")), ("n.xml", None), ("m.stl", None)];
        assert_eq!(models, want.map(|(f, m)| (f.to_string(), m.map(str::to_string))));
    }

    #[test]
    fn the_model_name_is_the_roots_non_empty_model_attribute() {
        assert_eq!(
            model_name(br#"<?xml version="1.0"?><mujoco model="arm"/>"#),
            Some("arm".into())
        );
        assert_eq!(model_name(br#"<mujoco model=""><x model="no"/></mujoco>"#), None);
        assert_eq!(model_name(b"<mujoco><worldbody model=\"no\"/></mujoco>"), None);
        assert_eq!(model_name(b"not xml <"), None);
    }
}
