//! Reads Mitsuba XML into a tree of plugin objects with typed properties.
//!
//! This stage knows the XML vocabulary (object tags, property tags, `default`, `include`, `ref`,
//! `transform`) but not the plugins: it substitutes `$name` parameters, checks attributes, parses
//! values and records where every element came from. The plugin stage then interprets the tree.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DMat4, DVec3};

use super::attrs::Attrs;
use super::transform::{TRANSFORM_OPS, operation_matrix};
use super::values::{
    parse_boolean, parse_float, parse_integer, parse_spectrum_pairs, parse_vec3_or_scalar, tokenize,
};
use crate::error::{LoadError, Loc, Result};
use crate::limits::{MAX_SCENE_FILE_BYTES, read_at_most};

/// Tags that create plugin objects.
const OBJECT_TAGS: [&str; 13] = [
    "scene",
    "integrator",
    "sensor",
    "film",
    "rfilter",
    "sampler",
    "shape",
    "bsdf",
    "emitter",
    "texture",
    "medium",
    "phase",
    "volume",
];

/// Tags that set a property of the enclosing object.
const PROPERTY_TAGS: [&str; 10] = [
    "float",
    "integer",
    "boolean",
    "string",
    "point",
    "vector",
    "rgb",
    "spectrum",
    "transform",
    "animation",
];

/// Other tags understood inside an object.
const OTHER_TAGS: [&str; 4] = ["ref", "default", "include", "path"];

/// How deeply `<include>` may nest before it is taken for a cycle.
const MAX_INCLUDE_DEPTH: usize = 16;

/// Longest attribute value after `$name` substitution, bytes.
const MAX_ATTRIBUTE_BYTES: usize = 1 << 20;

/// How deeply objects may nest (real scenes use at most about 5 levels); guards the recursion.
const MAX_OBJECT_DEPTH: usize = 32;

/// A typed property value.
#[derive(Debug, Clone)]
pub(crate) enum Value {
    Float(f64),
    Integer(i64),
    Boolean(bool),
    String(String),
    Point(DVec3),
    Vector(DVec3),
    Rgb(DVec3),
    /// A uniform spectrum (`<spectrum value="v"/>`).
    Spectrum(f64),
    /// A spectrum as wavelength (nm) and value pairs, `<spectrum value="400:0.1, 700:0.8"/>`:
    /// at least two, wavelengths increasing.
    SpectrumPairs(Vec<(f64, f64)>),
    Transform(DMat4),
    /// A transform that moves: `<animation>` with `<transform time="t">` keyframes (Strata's
    /// extension, after Mitsuba 0.6).
    Animation(geometry::AnimatedTransform),
}

impl Value {
    /// The XML tag that produces this kind of value, for messages.
    pub fn tag(&self) -> &'static str {
        match self {
            Value::Float(_) => "float",
            Value::Integer(_) => "integer",
            Value::Boolean(_) => "boolean",
            Value::String(_) => "string",
            Value::Point(_) => "point",
            Value::Vector(_) => "vector",
            Value::Rgb(_) => "rgb",
            Value::Spectrum(_) | Value::SpectrumPairs(_) => "spectrum",
            Value::Transform(_) => "transform",
            Value::Animation(_) => "animation",
        }
    }
}

/// One named property of an object.
#[derive(Debug, Clone)]
pub(crate) struct Prop {
    pub name: String,
    pub value: Value,
    pub loc: Loc,
}

/// A `<ref id="..."/>` to an object declared elsewhere.
#[derive(Debug, Clone)]
pub(crate) struct RefNode {
    pub id: String,
    /// The `name` attribute: the parameter the referenced object sets (a texture's).
    pub name: Option<String>,
    pub loc: Loc,
}

/// A nested object or a reference to one.
#[derive(Debug, Clone)]
pub(crate) enum Child {
    Object(ObjectNode),
    Ref(RefNode),
}

/// A plugin object element (`<shape type="obj">`, `<bsdf ...>`, the root `<scene>`).
#[derive(Debug, Clone)]
pub(crate) struct ObjectNode {
    /// The element's tag, e.g. `shape`.
    pub tag: String,
    /// The `type` attribute (empty for `<scene>`).
    pub plugin: String,
    /// The `id` attribute.
    pub id: Option<String>,
    /// The `name` attribute: the parameter a nested object sets (a texture's).
    pub name: Option<String>,
    /// Where the element is; `element` is its opening tag.
    pub loc: Loc,
    /// Properties in document order.
    pub props: Vec<Prop>,
    /// Nested objects and references in document order.
    pub children: Vec<Child>,
}

/// A `$name` parameter: from an override or from a `<default>`.
struct Param {
    name: String,
    value: String,
    used: bool,
    from_override: bool,
}

/// Parses the scene file at `path` with the given `$name` overrides into its root `<scene>` node.
pub(crate) fn parse_scene_file(path: &Path, overrides: &[(String, String)]) -> Result<ObjectNode> {
    parse_scene(path, None, overrides)
}

/// Parses `text` as the scene file at `path` (which names it in messages and resolves its
/// relative paths) with the given `$name` overrides into its root `<scene>` node.
pub(crate) fn parse_scene_text(
    path: &Path,
    text: &[u8],
    overrides: &[(String, String)],
) -> Result<ObjectNode> {
    parse_scene(path, Some(text), overrides)
}

/// Parses the scene at `path`, read from disk unless its `text` is given.
fn parse_scene(
    path: &Path,
    text: Option<&[u8]>,
    overrides: &[(String, String)],
) -> Result<ObjectNode> {
    let mut builder = Builder {
        params: overrides
            .iter()
            .map(|(name, value)| Param {
                name: name.clone(),
                value: value.clone(),
                used: false,
                from_override: true,
            })
            .collect(),
        ids: HashMap::new(),
        search_dirs: Vec::new(),
    };
    builder.sort_params();
    let file_loc = Loc::file_only(path);
    if let Some((i, (name, _))) = overrides
        .iter()
        .enumerate()
        .find(|(i, (name, _))| overrides[..*i].iter().any(|(other, _)| other == name))
    {
        return Err(file_loc.error(format!(
            "parameter {name} is overridden twice ({name}={} and {name}={})",
            overrides
                .iter()
                .find(|(other, _)| other == name)
                .map_or("", |o| &o.1),
            overrides[i].1
        )));
    }
    let mut root = match text {
        Some(text) => builder.parse_text(path, text.to_vec(), 0)?,
        None => builder.parse_file(path, 0, &file_loc)?,
    };
    let scene_dir = path.parent().unwrap_or(Path::new(""));
    resolve_filenames(&mut root, &builder.search_dirs, scene_dir);
    if root.tag != "scene" {
        return Err(root.loc.error(format!(
            "the root element must be <scene>, not <{}>",
            root.tag
        )));
    }
    if let Some(unused) = builder.params.iter().find(|p| p.from_override && !p.used) {
        return Err(file_loc.error(format!(
            "parameter override {}={} is not used: no attribute of the scene mentions ${}",
            unused.name, unused.value, unused.name
        )));
    }
    Ok(root)
}

struct Builder {
    /// Known parameters, longest name first so that `$ab` wins over `$a`.
    params: Vec<Param>,
    /// Where each `id` was first declared.
    ids: HashMap<String, Loc>,
    /// The folders `<path>` elements named, absolute, in document order.
    search_dirs: Vec<PathBuf>,
}

/// Resolves every relative `filename` property below `node` as Mitsuba's file resolver does
/// once `<path>` elements have added `search_dirs`: the first folder, latest added first, that
/// holds the file; else the folder of the file the property is in (where the plugins look, and
/// the scene's folder for the scene file itself); else the scene's folder, where Mitsuba looks
/// for the files an included file names. A file found nowhere is left for the plugin to report.
fn resolve_filenames(node: &mut ObjectNode, search_dirs: &[PathBuf], scene_dir: &Path) {
    for prop in &mut node.props {
        let (true, Value::String(name)) = (prop.name == "filename", &mut prop.value) else {
            continue;
        };
        let relative = Path::new(name.as_str());
        let own_dir = prop.loc.file.parent().unwrap_or(Path::new(""));
        let found = search(search_dirs, relative).or_else(|| {
            (!own_dir.join(relative).exists())
                .then(|| scene_dir.join(relative))
                .filter(|p| p.exists())
                .and_then(|p| std::fs::canonicalize(p).ok())
        });
        if let Some(found) = found {
            *name = found.to_string_lossy().into_owned();
        }
    }
    for child in &mut node.children {
        if let Child::Object(object) = child {
            resolve_filenames(object, search_dirs, scene_dir);
        }
    }
}

/// The first of `search_dirs`, latest first, that holds the relative path `name`, joined to it.
fn search(search_dirs: &[PathBuf], name: &Path) -> Option<PathBuf> {
    if name.is_absolute() {
        return None;
    }
    search_dirs
        .iter()
        .rev()
        .map(|dir| dir.join(name))
        .find(|candidate| candidate.exists())
}

impl Builder {
    fn sort_params(&mut self) {
        self.params.sort_by_key(|p| std::cmp::Reverse(p.name.len()));
    }

    /// Reads and parses one XML file and returns its root object. `origin` locates the element that
    /// asked for the file (the `<include>`, or the file itself for the scene).
    fn parse_file(&mut self, path: &Path, depth: usize, origin: &Loc) -> Result<ObjectNode> {
        let text = read_at_most(path, MAX_SCENE_FILE_BYTES)
            .map_err(|e| origin.error(format!("cannot read \"{}\": {e}", path.display())))?;
        self.parse_text(path, text, depth)
    }

    /// Parses `text`, the contents of the XML file at `path`, and returns its root object.
    fn parse_text(&mut self, path: &Path, text: Vec<u8>, depth: usize) -> Result<ObjectNode> {
        let text = String::from_utf8(text).map_err(|e| {
            let valid = String::from_utf8_lossy(&e.as_bytes()[..e.utf8_error().valid_up_to()]);
            let pos = end_position(&valid);
            LoadError {
                file: path.to_path_buf(),
                line: pos.row,
                column: pos.col,
                element: String::new(),
                message: "the file is not valid UTF-8 text (is it an XML scene?)".to_string(),
            }
        })?;
        let file = Arc::new(path.to_path_buf());
        let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
        let text = super::comments::tolerate_dashes(text);
        let text = text.as_ref();
        // A document type declaration is allowed, as Mitsuba's parser allows it (roxmltree
        // still refuses entity loops and exponential expansion).
        let options = roxmltree::ParsingOptions {
            allow_dtd: true,
            ..roxmltree::ParsingOptions::default()
        };
        let doc = roxmltree::Document::parse_with_options(text, options)
            .map_err(|e| syntax_error(&file, text, &e))?;
        let root = doc.root_element();
        let ctx = FileCtx {
            doc: &doc,
            file,
            dir: path.parent().map(Path::to_path_buf).unwrap_or_default(),
            depth,
        };
        let tag = root.tag_name().name();
        let attrs = self.attrs(&ctx, root)?;
        let loc = ctx.loc(root, &describe(tag, &attrs));
        if tag == "scene" {
            attrs.check(&["version", "type", "id", "name"], &["version"], &loc)?;
            check_version(attrs.get("version").unwrap_or_default(), &loc)?;
        } else if !OBJECT_TAGS.contains(&tag) {
            return Err(loc.error(format!(
                "the root element must be <scene> (or, in an included file, an object: {})",
                OBJECT_TAGS.join(", ")
            )));
        }
        self.object(&ctx, root, attrs, loc)
    }

    /// The substituted attributes of `node`.
    fn attrs(&mut self, ctx: &FileCtx, node: roxmltree::Node) -> Result<Attrs> {
        let mut attrs = Attrs::default();
        for attr in node.attributes() {
            let raw_loc = ctx.loc(node, &format!("<{}>", node.tag_name().name()));
            let value = self.substitute(attr.value(), &raw_loc)?;
            attrs.push(attr.name().to_string(), value);
        }
        Ok(attrs)
    }

    /// Replaces `$name` by parameter values, leaves `\$` as a literal `$`, and rejects undefined names.
    /// Parameters are replaced one after another, longest name first, each in one linear pass;
    /// a value growing past [`MAX_ATTRIBUTE_BYTES`] (parameters that double each other) is an error.
    fn substitute(&mut self, raw: &str, loc: &Loc) -> Result<String> {
        if !raw.contains('$') {
            return Ok(raw.to_string());
        }
        let mut value = raw.to_string();
        for param in &mut self.params {
            let key = format!("${}", param.name);
            if !value.contains(&key) {
                continue;
            }
            let mut replaced = String::with_capacity(value.len());
            let mut rest = value.as_str();
            while let Some(at) = rest.find(&key) {
                let before = &rest[..at];
                let escaped = before.ends_with('\\') || (at == 0 && replaced.ends_with('\\'));
                replaced.push_str(&rest[..at]);
                replaced.push_str(if escaped { &key } else { &param.value });
                param.used |= !escaped;
                rest = &rest[at + key.len()..];
                if replaced.len() + rest.len() > MAX_ATTRIBUTE_BYTES {
                    return Err(loc.error(format!(
                        "the attribute grows beyond {MAX_ATTRIBUTE_BYTES} bytes when ${} is \
                         substituted (parameters that expand each other?)",
                        param.name
                    )));
                }
            }
            replaced.push_str(rest);
            value = replaced;
        }
        let bytes = value.as_bytes();
        for (i, &b) in bytes.iter().enumerate() {
            if b == b'$' && (i == 0 || bytes[i - 1] != b'\\') {
                let name: String = value[i + 1..]
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                    .collect();
                return Err(loc.error(format!(
                    "undefined parameter ${name} (define it with <default name=\"{name}\" value=\"...\"/> or an override)"
                )));
            }
        }
        Ok(value.replace("\\$", "$"))
    }

    /// Builds an object node from `node`, whose attributes are `attrs`, located at `loc`.
    fn object(
        &mut self,
        ctx: &FileCtx,
        node: roxmltree::Node,
        attrs: Attrs,
        loc: Loc,
    ) -> Result<ObjectNode> {
        let tag = node.tag_name().name().to_string();
        if node.ancestors().count() > MAX_OBJECT_DEPTH {
            return Err(loc.error(format!(
                "elements nested deeper than {MAX_OBJECT_DEPTH} levels"
            )));
        }
        if tag != "scene" {
            attrs.check(&["type", "id", "name"], &["type"], &loc)?;
        }
        let id = attrs.get("id").map(str::to_string);
        if let Some(id) = &id {
            if let Some(previous) = self.ids.get(id) {
                return Err(loc.error(format!(
                    "duplicate id \"{id}\" (first declared at {}:{})",
                    previous.file.display(),
                    previous.line
                )));
            }
            self.ids.insert(id.clone(), loc.clone());
        }
        let mut object = ObjectNode {
            plugin: attrs.get("type").unwrap_or_default().to_string(),
            tag,
            id,
            name: attrs.get("name").map(str::to_string),
            loc,
            props: Vec::new(),
            children: Vec::new(),
        };
        for child in node.children() {
            if child.is_text() {
                let text = child.text().unwrap_or_default();
                if !text.trim().is_empty() {
                    let leading = text.len() - text.trim_start().len();
                    let text_loc = ctx.loc_at(child.range().start + leading, "text");
                    return Err(text_loc.error(format!(
                        "unexpected text \"{}\" inside {}",
                        text.trim(),
                        object.loc.element
                    )));
                }
                continue;
            }
            if child.is_element() {
                self.child(ctx, child, &mut object)?;
            }
        }
        Ok(object)
    }

    /// Handles one child element of an object.
    fn child(
        &mut self,
        ctx: &FileCtx,
        node: roxmltree::Node,
        parent: &mut ObjectNode,
    ) -> Result<()> {
        let tag = node.tag_name().name();
        let attrs = self.attrs(ctx, node)?;
        let loc = ctx.loc(node, &describe(tag, &attrs));
        let is_spectrum_object = tag == "spectrum" && attrs.get("type").is_some();
        if tag == "scene" {
            return Err(loc.error("<scene> cannot be nested"));
        }
        if OBJECT_TAGS.contains(&tag) || is_spectrum_object {
            let object = self.object(ctx, node, attrs, loc)?;
            parent.children.push(Child::Object(object));
            return Ok(());
        }
        if PROPERTY_TAGS.contains(&tag) {
            let prop = self.property(ctx, node, tag, &attrs, loc)?;
            if let Some(previous) = parent.props.iter().find(|p| p.name == prop.name) {
                return Err(prop.loc.error(format!(
                    "parameter \"{}\" is specified twice (first at line {})",
                    prop.name, previous.loc.line
                )));
            }
            parent.props.push(prop);
            return Ok(());
        }
        no_element_children(node, &loc)?;
        match tag {
            "ref" => {
                attrs.check(&["id", "name"], &["id"], &loc)?;
                let id = attrs.get("id").unwrap_or_default().to_string();
                let name = attrs.get("name").map(str::to_string);
                parent.children.push(Child::Ref(RefNode { id, name, loc }));
                Ok(())
            }
            "default" => {
                attrs.check(&["name", "value"], &["name", "value"], &loc)?;
                let name = attrs.get("name").unwrap_or_default();
                if name.is_empty() {
                    return Err(loc.error("<default> needs a non-empty name"));
                }
                if !self.params.iter().any(|p| p.name == name) {
                    self.params.push(Param {
                        name: name.to_string(),
                        value: attrs.get("value").unwrap_or_default().to_string(),
                        used: false,
                        from_override: false,
                    });
                    self.sort_params();
                }
                Ok(())
            }
            "include" => {
                attrs.check(&["filename", "name"], &["filename"], &loc)?;
                if ctx.depth + 1 >= MAX_INCLUDE_DEPTH {
                    return Err(loc.error(format!(
                        "includes nested deeper than {MAX_INCLUDE_DEPTH} levels (an include cycle?)"
                    )));
                }
                // The including file's folder first, then `<path>` folders, as Mitsuba's.
                let filename = Path::new(attrs.get("filename").unwrap_or_default());
                let path = Some(ctx.dir.join(filename))
                    .filter(|p| p.is_file())
                    .or_else(|| search(&self.search_dirs, filename))
                    .unwrap_or_else(|| ctx.dir.join(filename));
                if !path.is_file() {
                    return Err(
                        loc.error(format!("included file \"{}\" not found", path.display()))
                    );
                }
                let included = self.parse_file(&path, ctx.depth + 1, &loc)?;
                if included.tag == "scene" {
                    parent.props.extend(included.props);
                    parent.children.extend(included.children);
                } else {
                    parent.children.push(Child::Object(included));
                }
                Ok(())
            }
            "path" => {
                attrs.check(&["value"], &["value"], &loc)?;
                let value = Path::new(attrs.get("value").unwrap_or_default());
                let dir = Some(ctx.dir.join(value))
                    .filter(|d| d.is_dir())
                    .or_else(|| search(&self.search_dirs, value).filter(|d| d.is_dir()))
                    .and_then(|d| std::fs::canonicalize(d).ok())
                    .ok_or_else(|| {
                        loc.error(format!("folder \"{}\" not found", value.display()))
                    })?;
                self.search_dirs.push(dir);
                Ok(())
            }
            _ if TRANSFORM_OPS.contains(&tag) => {
                Err(loc.error(format!("<{tag}> can only appear inside <transform>")))
            }
            _ => Err(loc.error(format!(
                "unknown or unsupported element <{tag}> (supported: {}, {}, {})",
                OBJECT_TAGS[1..].join(", "),
                PROPERTY_TAGS.join(", "),
                OTHER_TAGS.join(", ")
            ))),
        }
    }

    /// Parses a property element into a named value.
    fn property(
        &mut self,
        ctx: &FileCtx,
        node: roxmltree::Node,
        tag: &str,
        attrs: &Attrs,
        loc: Loc,
    ) -> Result<Prop> {
        let name = || attrs.get("name").unwrap_or_default().to_string();
        let value_text = || attrs.get("value").unwrap_or_default();
        if tag == "transform" {
            attrs.check(&["name"], &["name"], &loc)?;
            let matrix = self.transform(ctx, node)?;
            return Ok(Prop {
                name: name(),
                value: Value::Transform(matrix),
                loc,
            });
        }
        if tag == "animation" {
            attrs.check(&["name"], &["name"], &loc)?;
            let animation = self.animation(ctx, node, &loc)?;
            return Ok(Prop {
                name: name(),
                value: Value::Animation(animation),
                loc,
            });
        }
        no_element_children(node, &loc)?;
        let value = match tag {
            "float" | "integer" | "boolean" | "string" | "rgb" => {
                attrs.check(&["name", "value"], &["name", "value"], &loc)?;
                match tag {
                    "float" => Value::Float(parse_float(value_text(), &loc)?),
                    "integer" => Value::Integer(parse_integer(value_text(), &loc)?),
                    "boolean" => Value::Boolean(parse_boolean(value_text(), &loc)?),
                    "string" => Value::String(value_text().to_string()),
                    _ => Value::Rgb(parse_vec3_or_scalar(value_text(), &loc)?),
                }
            }
            "point" | "vector" => {
                attrs.check(&["name", "value", "x", "y", "z"], &["name"], &loc)?;
                let v = point_value(attrs, &loc)?;
                if tag == "point" {
                    Value::Point(v)
                } else {
                    Value::Vector(v)
                }
            }
            _ => {
                attrs.check(&["name", "value", "filename"], &["name"], &loc)?;
                if attrs.get("filename").is_some() {
                    return Err(loc.error(
                        "spectra from files are not supported (use <rgb>, a single value or wavelength:value pairs)",
                    ));
                }
                let text = attrs
                    .get("value")
                    .ok_or_else(|| loc.error("missing required attribute \"value\""))?;
                if text.contains(':') {
                    Value::SpectrumPairs(parse_spectrum_pairs(text, &loc)?)
                } else if tokenize(text).len() == 1 {
                    Value::Spectrum(parse_float(text, &loc)?)
                } else {
                    return Err(loc.error(
                        "a spectrum is one value or wavelength:value pairs (\"400:0.5, 700:0.8\")",
                    ));
                }
            }
        };
        Ok(Prop {
            name: name(),
            value,
            loc,
        })
    }

    /// The transform an `<animation>` describes by `<transform time="t">` keyframes, at least
    /// two, times strictly increasing, each matrix a translation, rotation and scale.
    fn animation(
        &mut self,
        ctx: &FileCtx,
        node: roxmltree::Node,
        loc: &Loc,
    ) -> Result<geometry::AnimatedTransform> {
        let mut keyframes = Vec::new();
        let mut locs = Vec::new();
        for child in node.children() {
            if child.is_text() && !child.text().unwrap_or_default().trim().is_empty() {
                return Err(ctx
                    .loc(child, "text")
                    .error("unexpected text inside <animation>"));
            }
            if !child.is_element() {
                continue;
            }
            let tag = child.tag_name().name();
            let attrs = self.attrs(ctx, child)?;
            let child_loc = ctx.loc(child, &describe(tag, &attrs));
            if tag != "transform" {
                return Err(child_loc.error(format!(
                    "unexpected <{tag}> inside <animation> (only <transform time=\"...\"> keyframes)"
                )));
            }
            attrs.check(&["time"], &["time"], &child_loc)?;
            let time = parse_float(attrs.get("time").unwrap_or_default(), &child_loc)?;
            keyframes.push((time, self.transform(ctx, child)?));
            locs.push(child_loc);
        }
        geometry::AnimatedTransform::new(&keyframes).map_err(|error| {
            let at = match error {
                geometry::AnimationError::TooFewKeyframes => loc,
                geometry::AnimationError::TimesNotIncreasing { index }
                | geometry::AnimationError::NotDecomposable { index, .. } => &locs[index],
            };
            at.error(error.to_string())
        })
    }

    /// Composes the operations inside a `<transform>` in document order (`M = op * M`).
    fn transform(&mut self, ctx: &FileCtx, node: roxmltree::Node) -> Result<DMat4> {
        let mut matrix = DMat4::IDENTITY;
        for op in node.children() {
            if op.is_text() && !op.text().unwrap_or_default().trim().is_empty() {
                return Err(ctx
                    .loc(op, "text")
                    .error("unexpected text inside <transform>"));
            }
            if !op.is_element() {
                continue;
            }
            let tag = op.tag_name().name();
            let attrs = self.attrs(ctx, op)?;
            let loc = ctx.loc(op, &describe(tag, &attrs));
            no_element_children(op, &loc)?;
            matrix = operation_matrix(tag, &attrs, &loc)? * matrix;
        }
        Ok(matrix)
    }
}

/// What the tree builder needs to know about the file being read.
struct FileCtx<'a, 'input> {
    doc: &'a roxmltree::Document<'input>,
    file: Arc<PathBuf>,
    dir: PathBuf,
    depth: usize,
}

impl FileCtx<'_, '_> {
    /// The location of `node` in this file, shown as `element`.
    fn loc(&self, node: roxmltree::Node, element: &str) -> Loc {
        self.loc_at(node.range().start, element)
    }

    /// The location of byte offset `offset` in this file, shown as `element`.
    fn loc_at(&self, offset: usize, element: &str) -> Loc {
        let pos = self.doc.text_pos_at(offset);
        Loc {
            file: self.file.clone(),
            line: pos.row,
            column: pos.col,
            element: element.to_string(),
        }
    }
}

/// The opening tag with its identifying attributes, e.g. `<shape type="obj" id="floor">`.
fn describe(tag: &str, attrs: &Attrs) -> String {
    let mut text = format!("<{tag}");
    for key in ["type", "id", "name", "value"] {
        if let Some(v) = attrs.get(key) {
            if key == "value" && (!PROPERTY_TAGS.contains(&tag) || v.len() > 40) {
                continue;
            }
            text.push_str(&format!(" {key}=\"{v}\""));
        }
    }
    text.push('>');
    text
}

/// A point or vector from `value` (1 or 3 numbers) or from all of `x`, `y`, `z`.
fn point_value(attrs: &Attrs, loc: &Loc) -> Result<DVec3> {
    if let Some(value) = attrs.get("value") {
        if attrs.get("x").is_some() || attrs.get("y").is_some() || attrs.get("z").is_some() {
            return Err(loc.error("cannot mix \"value\" with \"x\"/\"y\"/\"z\" attributes"));
        }
        return parse_vec3_or_scalar(value, loc);
    }
    let mut v = [0.0; 3];
    for (i, key) in ["x", "y", "z"].iter().enumerate() {
        let text = attrs.get(key).ok_or_else(|| {
            loc.error(format!(
                "missing attribute \"{key}\" (give \"value\" or all of \"x\", \"y\", \"z\")"
            ))
        })?;
        v[i] = parse_float(text, loc)?;
    }
    Ok(DVec3::from_array(v))
}

/// Fails when a property-like element has element children.
fn no_element_children(node: roxmltree::Node, loc: &Loc) -> Result<()> {
    if let Some(child) = node.children().find(|c| c.is_element()) {
        return Err(loc.error(format!(
            "<{}> cannot contain <{}>",
            node.tag_name().name(),
            child.tag_name().name()
        )));
    }
    Ok(())
}

/// Accepts Mitsuba scene versions 2.x and 3.x.
fn check_version(version: &str, loc: &Loc) -> Result<()> {
    let parts: Vec<&str> = version.trim().split('.').collect();
    let numeric = !parts.is_empty()
        && parts.len() <= 3
        && parts
            .iter()
            .all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()));
    if !numeric {
        return Err(loc.error(format!(
            "invalid version \"{version}\" (expected e.g. \"3.0.0\")"
        )));
    }
    match parts[0] {
        "2" | "3" => Ok(()),
        _ => Err(loc.error(format!(
            "unsupported scene version \"{version}\" (supported: 2.x and 3.x)"
        ))),
    }
}

/// An XML syntax error at its position. A file that ends too early is reported at its end,
/// naming the innermost element still open and where it was opened.
fn syntax_error(file: &Arc<PathBuf>, text: &str, error: &roxmltree::Error) -> LoadError {
    let truncated = matches!(
        error,
        roxmltree::Error::UnclosedRootNode | roxmltree::Error::UnexpectedEndOfStream
    );
    if truncated {
        // The end of the last line that has text.
        let end = end_position(text.trim_end_matches(['\r', '\n']));
        let (element, message) = match innermost_open_element(text) {
            Some((name, offset)) => {
                let opened = end_position(&text[..offset]);
                (
                    format!("<{name}>"),
                    format!(
                        "XML syntax error: the file ends inside <{name}> (opened at line {}, column {})",
                        opened.row, opened.col
                    ),
                )
            }
            None => (String::new(), format!("XML syntax error: {error}")),
        };
        return LoadError {
            file: file.as_ref().clone(),
            line: end.row,
            column: end.col,
            element,
            message,
        };
    }
    let pos = error.pos();
    LoadError {
        file: file.as_ref().clone(),
        line: pos.row,
        column: pos.col,
        element: String::new(),
        message: format!("XML syntax error: {error}"),
    }
}

/// The 1-based line and column just after the end of `text`.
fn end_position(text: &str) -> roxmltree::TextPos {
    let line = text.matches('\n').count() + 1;
    let last_line = text.rsplit('\n').next().unwrap_or_default();
    roxmltree::TextPos::new(
        u32::try_from(line).unwrap_or(u32::MAX),
        u32::try_from(last_line.chars().count() + 1).unwrap_or(u32::MAX),
    )
}

/// The innermost element still open at the end of `text` and the byte offset of its `<`: a light
/// scan of start and end tags, skipping comments, declarations and processing instructions, for
/// messages about truncated files.
fn innermost_open_element(text: &str) -> Option<(&str, usize)> {
    let mut open: Vec<(&str, usize)> = Vec::new();
    let mut i = 0;
    while let Some(found) = text[i..].find('<') {
        let start = i + found;
        let rest = &text[start + 1..];
        let terminator = if rest.starts_with("!--") { "-->" } else { ">" };
        let end = rest
            .find(terminator)
            .map(|e| start + 1 + e + terminator.len());
        if !(rest.starts_with('!') || rest.starts_with('?')) {
            let closing = rest.starts_with('/');
            let name_text = if closing { &rest[1..] } else { rest };
            let name_len = name_text
                .find(|c: char| c.is_whitespace() || c == '/' || c == '>')
                .unwrap_or(name_text.len());
            let self_closing = end.is_some_and(|e| text[..e - 1].ends_with('/'));
            if closing {
                open.pop();
            } else if !self_closing && name_len > 0 {
                open.push((&name_text[..name_len], start));
            }
        }
        match end {
            Some(e) => i = e,
            None => break,
        }
    }
    open.pop()
}
