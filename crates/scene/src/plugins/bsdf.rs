//! `<bsdf>`: diffuse, conductor, roughconductor, dielectric, roughdielectric, thindielectric,
//! plastic, roughplastic, twosided, blendbsdf, mask, null, normalmap and bumpmap, plus the table of BSDFs
//! that shapes index and `<ref id>` resolves into.

use std::collections::HashMap;
use std::sync::Arc;

use super::texture::{TextureDesc, texture};
use super::{child_loc, unexpected_child, unknown_type};
use crate::desc::{BsdfDesc, MicrofacetDistribution, Roughness};
use crate::error::Result;
use crate::ior::{CONDUCTORS, ior_names, lookup_conductor, lookup_ior};
use crate::params::{ColorKind, Params};
use crate::xml::tree::{Child, ObjectNode, RefNode};
use materials::{AdapterOptions, Bsdf, BsdfFlags, BumpMap, NormalMap};

/// How one `<bsdf>` plugin's element is read into a description: its parameters, nested
/// objects and their checks, with errors at the element's line.
type Reader<'a> = fn(&mut BsdfTable<'a>, &'a ObjectNode) -> Result<BsdfDesc>;

/// The BSDF plugins this loader understands, one line each: Mitsuba's plugin name and the
/// function that reads its XML parameters. A plugin whose reader builds the runtime BSDF at once
/// ([`BsdfDesc::Built`]) needs nothing else in the loader.
fn plugins<'a>() -> [(&'static str, Reader<'a>); 14] {
    [
        ("diffuse", BsdfTable::one_sided),
        ("conductor", BsdfTable::one_sided),
        ("roughconductor", BsdfTable::one_sided),
        ("dielectric", BsdfTable::one_sided),
        ("roughdielectric", BsdfTable::one_sided),
        ("thindielectric", BsdfTable::one_sided),
        ("plastic", BsdfTable::one_sided),
        ("roughplastic", BsdfTable::one_sided),
        ("twosided", BsdfTable::twosided),
        ("blendbsdf", BsdfTable::blend),
        ("mask", BsdfTable::mask),
        ("null", BsdfTable::one_sided),
        ("normalmap", BsdfTable::normalmap),
        ("bumpmap", BsdfTable::bumpmap),
    ]
}

/// The booleans both adapters, `normalmap` and `bumpmap`, take: Mitsuba 3.9's
/// `flip_invalid_normals` and `use_shadowing_function`, each true by default.
fn adapter_options(params: &mut Params) -> Result<AdapterOptions> {
    let defaults = AdapterOptions::default();
    Ok(AdapterOptions {
        flip_invalid_normals: params
            .boolean_or("flip_invalid_normals", defaults.flip_invalid_normals)?,
        shadowing_function: params
            .boolean_or("use_shadowing_function", defaults.shadowing_function)?,
    })
}

/// The names of [`plugins`], for error messages.
fn supported() -> Vec<&'static str> {
    plugins().iter().map(|(name, _)| *name).collect()
}

/// The BSDFs of a scene, filled as shapes and references ask for them.
pub(crate) struct BsdfTable<'a> {
    /// Every object in the scene that has an `id`.
    by_id: HashMap<&'a str, &'a ObjectNode>,
    /// Table index of each BSDF id interpreted so far.
    resolved: HashMap<&'a str, usize>,
    /// Ids being interpreted right now, to catch reference cycles.
    resolving: Vec<&'a str>,
    bsdfs: Vec<BsdfDesc>,
    default: Option<usize>,
    black: Option<usize>,
}

impl<'a> BsdfTable<'a> {
    /// An empty table that can resolve references to any object with an id below `root`.
    pub fn new(root: &'a ObjectNode) -> Self {
        let mut by_id = HashMap::new();
        collect_ids(root, &mut by_id);
        Self {
            by_id,
            resolved: HashMap::new(),
            resolving: Vec::new(),
            bsdfs: Vec::new(),
            default: None,
            black: None,
        }
    }

    /// Adds the `<bsdf>` element `node` (once, if it has an id) and returns its index.
    pub fn add(&mut self, node: &'a ObjectNode) -> Result<usize> {
        match node.id.as_deref() {
            Some(_) => self.add_with_id(node),
            None => {
                let bsdf = self.interpret(node)?;
                self.bsdfs.push(bsdf);
                Ok(self.bsdfs.len() - 1)
            }
        }
    }

    /// The index of the BSDF a `<ref>` names.
    pub fn reference(&mut self, reference: &RefNode) -> Result<usize> {
        let node = self.referenced(reference, "bsdf")?;
        self.add_with_id(node)
    }

    /// The object a `<ref>` names when it is an `<emitter>` (an area emitter declared at the top
    /// level and referenced from the shape that emits), `None` when it names something else.
    pub fn referenced_emitter(&self, reference: &RefNode) -> Option<&'a ObjectNode> {
        self.by_id
            .get(reference.id.as_str())
            .copied()
            .filter(|node| node.tag == "emitter")
    }

    /// The index of Mitsuba's default BSDF (diffuse, reflectance 0.5), added on first use.
    pub fn default_bsdf(&mut self) -> usize {
        *self.default.get_or_insert_with(|| {
            self.bsdfs.push(BsdfDesc::default_diffuse());
            self.bsdfs.len() - 1
        })
    }

    /// The index of the black BSDF Mitsuba gives emitting shapes that name none, added on
    /// first use.
    pub fn black_bsdf(&mut self) -> usize {
        *self.black.get_or_insert_with(|| {
            self.bsdfs.push(BsdfDesc::Diffuse {
                reflectance: glam::Vec3::ZERO,
            });
            self.bsdfs.len() - 1
        })
    }

    /// The finished table.
    pub fn into_bsdfs(self) -> Vec<BsdfDesc> {
        self.bsdfs
    }

    /// Interprets the BSDF `node`, which has an id, once and returns its index.
    fn add_with_id(&mut self, node: &'a ObjectNode) -> Result<usize> {
        let id: &'a str = node.id.as_deref().unwrap_or_default();
        if let Some(&index) = self.resolved.get(id) {
            return Ok(index);
        }
        if self.resolving.contains(&id) {
            return Err(node
                .loc
                .error(format!("circular reference: bsdf \"{id}\" contains itself")));
        }
        self.resolving.push(id);
        let bsdf = self.interpret(node);
        self.resolving.pop();
        self.bsdfs.push(bsdf?);
        let index = self.bsdfs.len() - 1;
        self.resolved.insert(id, index);
        Ok(index)
    }

    /// Interprets one `<bsdf>` element and checks that the renderer can build it, so that a
    /// value it rejects (an index of refraction too large for single precision) is reported
    /// with the element's line.
    fn interpret(&mut self, node: &'a ObjectNode) -> Result<BsdfDesc> {
        let Some((_, read)) = plugins().into_iter().find(|(name, _)| *name == node.plugin) else {
            return Err(unknown_type(node, &supported()));
        };
        let bsdf = read(self, node)?;
        crate::build::build_bsdf(&bsdf).map_err(|message| node.loc.error(message))?;
        Ok(bsdf)
    }

    /// Interprets a `<bsdf>` element other than `twosided`.
    fn one_sided(&mut self, node: &'a ObjectNode) -> Result<BsdfDesc> {
        let texture_name = match node.plugin.as_str() {
            "diffuse" => Some("reflectance"),
            "plastic" | "roughplastic" => Some("diffuse_reflectance"),
            _ => None,
        };
        let texture = match texture_name {
            Some(name) => self.texture_param(node, name, &[])?,
            None => {
                refuse_textured_roughness(node)?;
                super::no_children(node)?;
                None
            }
        };
        let mut params = Params::new(node);
        if let (Some(name), Some(_)) = (texture_name, &texture)
            && params.has(name)
        {
            return Err(params.loc_of(name).error(format!(
                "\"{name}\" is given twice (as a value and as a texture)"
            )));
        }
        let bsdf = match node.plugin.as_str() {
            "diffuse" => {
                let reflectance = rgb(&mut params, "reflectance", ColorKind::Reflectance, 0.5)?;
                textured(texture, reflectance, |reflectance| BsdfDesc::Diffuse {
                    reflectance,
                })
            }
            "conductor" => {
                let (eta, k) = conductor_ior(&mut params)?;
                BsdfDesc::Conductor {
                    eta,
                    k,
                    specular_reflectance: specular_reflectance(&mut params)?,
                }
            }
            "roughconductor" => {
                let (eta, k) = conductor_ior(&mut params)?;
                BsdfDesc::RoughConductor {
                    distribution: distribution(&mut params)?,
                    alpha: roughness(&mut params)?,
                    eta,
                    k,
                    specular_reflectance: specular_reflectance(&mut params)?,
                }
            }
            "dielectric" => {
                let (int_ior, ext_ior) = distinct_iors(&mut params, 1.5046)?;
                BsdfDesc::Dielectric {
                    int_ior,
                    ext_ior,
                    specular_reflectance: specular_reflectance(&mut params)?,
                    specular_transmittance: specular_transmittance(&mut params)?,
                }
            }
            "roughdielectric" => {
                let (int_ior, ext_ior) = distinct_iors(&mut params, 1.5046)?;
                BsdfDesc::RoughDielectric {
                    distribution: distribution(&mut params)?,
                    alpha: roughness(&mut params)?,
                    int_ior,
                    ext_ior,
                    specular_reflectance: specular_reflectance(&mut params)?,
                    specular_transmittance: specular_transmittance(&mut params)?,
                }
            }
            "null" => null_bsdf(),
            "thindielectric" => BsdfDesc::ThinDielectric {
                int_ior: ior(&mut params, "int_ior", 1.5046)? as f32,
                ext_ior: ior(&mut params, "ext_ior", 1.000277)? as f32,
                specular_reflectance: specular_reflectance(&mut params)?,
                specular_transmittance: specular_transmittance(&mut params)?,
            },
            "plastic" => {
                let int_ior = ior(&mut params, "int_ior", 1.49)? as f32;
                let ext_ior = ior(&mut params, "ext_ior", 1.000277)? as f32;
                let (diffuse_reflectance, specular_reflectance, nonlinear) = coating(&mut params)?;
                textured(texture, diffuse_reflectance, |diffuse_reflectance| {
                    BsdfDesc::Plastic {
                        int_ior,
                        ext_ior,
                        diffuse_reflectance,
                        specular_reflectance,
                        nonlinear,
                    }
                })
            }
            "roughplastic" => {
                let (int_ior, ext_ior) = distinct_iors(&mut params, 1.49)?;
                let distribution = distribution(&mut params)?;
                let alpha = alpha(&mut params)?;
                let (diffuse_reflectance, specular_reflectance, nonlinear) = coating(&mut params)?;
                textured(texture, diffuse_reflectance, |diffuse_reflectance| {
                    BsdfDesc::RoughPlastic {
                        distribution,
                        alpha,
                        int_ior,
                        ext_ior,
                        diffuse_reflectance,
                        specular_reflectance,
                        nonlinear,
                    }
                })
            }
            _ => return Err(unknown_type(node, &supported())),
        };
        params.finish()?;
        Ok(bsdf)
    }

    /// `twosided` with one nested BSDF (both sides) or two (front, back).
    fn twosided(&mut self, node: &'a ObjectNode) -> Result<BsdfDesc> {
        Params::new(node).finish()?;
        let mut sides = Vec::new();
        for (child, bsdf) in self.nested(node, None)? {
            match bsdf {
                BsdfDesc::TexturedBlend { .. } => {
                    return Err(child_loc(child).error(
                        "twosided around a blendbsdf or mask with a bitmap is not supported",
                    ));
                }
                BsdfDesc::TwoSided { .. }
                | BsdfDesc::Dielectric { .. }
                | BsdfDesc::RoughDielectric { .. }
                | BsdfDesc::ThinDielectric { .. } => {
                    return Err(child_loc(child).error(
                        "twosided can only wrap one-sided reflective BSDFs (not twosided, dielectric, roughdielectric or thindielectric)",
                    ));
                }
                BsdfDesc::Blend { .. } if bsdf_has_transmission(&bsdf) => {
                    return Err(child_loc(child).error(
                        "twosided can only wrap reflective BSDFs, as in Mitsuba; this blend or mask transmits (a dielectric, thindielectric, null or mask in it)",
                    ));
                }
                bsdf => sides.push(bsdf),
            }
        }
        let mut sides = sides.into_iter();
        let front = sides
            .next()
            .ok_or_else(|| node.loc.error("twosided needs a nested BSDF"))?;
        let back = sides.next().unwrap_or_else(|| front.clone());
        let two_sided = |[front, back]: [BsdfDesc; 2]| BsdfDesc::TwoSided {
            front: Box::new(front),
            back: Box::new(back),
        };
        match (&front, &back) {
            (
                BsdfDesc::DiffuseBitmap {
                    base: front_base,
                    texture,
                },
                BsdfDesc::DiffuseBitmap {
                    base: back_base,
                    texture: back_texture,
                },
            ) if Arc::ptr_eq(texture, back_texture) => Ok(BsdfDesc::DiffuseBitmap {
                base: Box::new(two_sided([(**front_base).clone(), (**back_base).clone()])),
                texture: texture.clone(),
            }),
            (BsdfDesc::DiffuseBitmap { .. }, _) | (_, BsdfDesc::DiffuseBitmap { .. }) => {
                Err(node.loc.error(
                    "a twosided BSDF with a bitmap texture must show the same BSDF on both sides",
                ))
            }
            _ => hoist_checkerboard(node, [front, back], two_sided),
        }
    }

    /// The BSDFs nested in `node` (objects or references), each with the child it came from: one
    /// or two, else an error at the element. A texture or reference named `texture_name` is
    /// passed over (a blend's weight).
    fn nested(
        &mut self,
        node: &'a ObjectNode,
        texture_name: Option<&str>,
    ) -> Result<Vec<(&'a Child, BsdfDesc)>> {
        let mut found = Vec::new();
        for child in &node.children {
            let named = match child {
                Child::Object(object) if object.tag == "texture" => object.name.as_deref(),
                Child::Ref(reference) => reference.name.as_deref(),
                Child::Object(_) => None,
            };
            if texture_name.is_some() && named == texture_name {
                continue;
            }
            if found.len() == 2 {
                return Err(unexpected_child(node, child, "one or two BSDFs"));
            }
            let bsdf = match child {
                Child::Object(object) if object.tag == "bsdf" => match object.id {
                    Some(_) => {
                        let index = self.add(object)?;
                        self.bsdfs[index].clone()
                    }
                    None => self.interpret(object)?,
                },
                Child::Ref(reference) => {
                    let index = self.reference(reference)?;
                    self.bsdfs[index].clone()
                }
                Child::Object(_) => return Err(unexpected_child(node, child, "one or two BSDFs")),
            };
            found.push((child, bsdf));
        }
        Ok(found)
    }

    /// `blendbsdf`: exactly two nested BSDFs and a `weight`: a constant in [0, 1], or a
    /// `checkerboard` or `bitmap` texture read as Mitsuba's `eval_1` reads it (a checkerboard's
    /// colours by their mean over RGB, `color0` on the squares where exactly one of u and v has a
    /// fractional part above ½, the other way round from its colour lookups; a bitmap by its
    /// luminance), clamped to [0, 1] as Mitsuba clamps it.
    fn blend(&mut self, node: &'a ObjectNode) -> Result<BsdfDesc> {
        let (weight_texture, weight) = self.weight_param(node, "weight", None)?;
        let mut nested = self
            .nested(node, Some("weight"))?
            .into_iter()
            .map(|(_, bsdf)| bsdf);
        let (Some(first), Some(second), None) = (nested.next(), nested.next(), nested.next())
        else {
            return Err(node.loc.error("blendbsdf needs two nested BSDFs"));
        };
        blended(node, [first, second], weight_texture, weight)
    }

    /// `mask`: one nested BSDF seen with probability `opacity` (a constant in [0, 1], default
    /// ½, or a texture read as [`Self::blend`] reads a weight), the rest passing straight
    /// through as Mitsuba's null BSDF: Mitsuba's `mask` is exactly a `blendbsdf` of `null`
    /// (weight 0) and the nested BSDF (weight 1), down to its sampling and densities.
    fn mask(&mut self, node: &'a ObjectNode) -> Result<BsdfDesc> {
        let (opacity_texture, opacity) = self.weight_param(node, "opacity", Some(0.5))?;
        let mut nested = self
            .nested(node, Some("opacity"))?
            .into_iter()
            .map(|(_, bsdf)| bsdf);
        let (Some(inner), None) = (nested.next(), nested.next()) else {
            return Err(node.loc.error("mask needs exactly one nested BSDF"));
        };
        blended(node, [null_bsdf(), inner], opacity_texture, opacity)
    }

    /// `normalmap`: one nested BSDF, a `bitmap` texture named `normalmap` whose RGB encodes
    /// the shading normal, and the booleans of [`adapter_options`] ([`NormalMap`]).
    fn normalmap(&mut self, node: &'a ObjectNode) -> Result<BsdfDesc> {
        let texture = self.adapter_texture(node, "normalmap")?;
        let mut params = Params::new(node);
        let options = adapter_options(&mut params)?;
        params.finish()?;
        let nested = self.adapter_nested(node, "normalmap")?;
        Ok(BsdfDesc::Built(
            NormalMap::new(nested, texture, options).into(),
        ))
    }

    /// `bumpmap`: one nested BSDF, a `bitmap` texture (of any name, as in Mitsuba) whose
    /// luminance times `scale` (default 1) is the height field, and the booleans of
    /// [`adapter_options`] ([`BumpMap`]).
    fn bumpmap(&mut self, node: &'a ObjectNode) -> Result<BsdfDesc> {
        let name = node
            .children
            .iter()
            .find_map(|child| match child {
                Child::Object(object) if object.tag == "texture" => object.name.as_deref(),
                Child::Ref(reference) => reference.name.as_deref(),
                Child::Object(_) => None,
            })
            .unwrap_or("bumpmap");
        let texture = self.adapter_texture(node, name)?;
        let mut params = Params::new(node);
        let scale = params.float_or("scale", 1.0)?;
        if !scale.is_finite() {
            return Err(params.loc_of("scale").error("\"scale\" must be finite"));
        }
        let options = adapter_options(&mut params)?;
        params.finish()?;
        let nested = self.adapter_nested(node, name)?;
        Ok(BsdfDesc::Built(
            BumpMap::new(nested, texture, scale as f32, options).into(),
        ))
    }

    /// The `bitmap` texture named `name` of a BSDF adapter, or an error at the element.
    fn adapter_texture(
        &self,
        node: &'a ObjectNode,
        name: &str,
    ) -> Result<Arc<materials::BitmapTexture>> {
        match self.texture_param(node, name, &["bsdf"])? {
            Some(TextureDesc::Bitmap(texture)) => Ok(texture),
            Some(TextureDesc::Checkerboard { .. }) => Err(node.loc.error(format!(
                "{}: the texture \"{name}\" must be a bitmap (a checkerboard is not supported)",
                node.plugin
            ))),
            None => Err(node.loc.error(format!(
                "{} needs a <texture type=\"bitmap\" name=\"{name}\">",
                node.plugin
            ))),
        }
    }

    /// The one nested BSDF of an adapter whose texture is named `texture_name`, built: an error
    /// at the element when there is none or more, or when it is textured or an adapter itself.
    fn adapter_nested(&mut self, node: &'a ObjectNode, texture_name: &str) -> Result<Bsdf> {
        let mut nested = self.nested(node, Some(texture_name))?.into_iter();
        let (Some((child, inner)), None) = (nested.next(), nested.next()) else {
            return Err(node
                .loc
                .error(format!("{} needs exactly one nested BSDF", node.plugin)));
        };
        if matches!(
            inner,
            BsdfDesc::Checkerboard { .. }
                | BsdfDesc::DiffuseBitmap { .. }
                | BsdfDesc::TexturedBlend { .. }
        ) {
            return Err(child_loc(child).error(format!(
                "a {} around a textured BSDF is not supported (give its parameters as values)",
                node.plugin
            )));
        }
        let bsdf = crate::build::build_bsdf(&inner).map_err(|m| child_loc(child).error(m))?;
        if bsdf.flags().contains(BsdfFlags::AT_SURFACE) {
            return Err(child_loc(child).error(format!(
                "a {} around a normalmap or bumpmap is not supported",
                node.plugin
            )));
        }
        Ok(bsdf)
    }

    /// A blend weight named `name` of `node` (`blendbsdf`'s `weight`, `mask`'s `opacity`): a
    /// texture, or a constant in [0, 1] (`default` when absent, an error when there is none),
    /// and the constant ½ beside a texture; an error when given both ways. Checks the node's
    /// other parameters too.
    fn weight_param(
        &self,
        node: &'a ObjectNode,
        name: &'static str,
        default: Option<f64>,
    ) -> Result<(Option<TextureDesc>, f32)> {
        let texture = self.texture_param(node, name, &["bsdf"])?;
        let mut params = Params::new(node);
        let weight = params.float(name)?;
        let weight = match (&texture, weight.or(default)) {
            (Some(_), Some(_)) if params.has(name) => {
                return Err(params.loc_of(name).error(format!(
                    "\"{name}\" is given twice (as a value and as a texture)"
                )));
            }
            (None, None) => {
                return Err(node.loc.error(format!(
                    "missing required parameter \"{name}\" (a float in [0, 1] or a texture)"
                )));
            }
            (None, Some(weight)) if !(0.0..=1.0).contains(&weight) => {
                return Err(params
                    .loc_of(name)
                    .error(format!("\"{name}\" must be in [0, 1], got {weight}")));
            }
            (Some(_), _) => 0.5,
            (None, Some(weight)) => weight as f32,
        };
        params.finish()?;
        Ok((texture, weight))
    }
    /// The object with a `tag` element that `reference` names, or an error at the reference.
    fn referenced(&self, reference: &RefNode, tag: &str) -> Result<&'a ObjectNode> {
        let Some(&node) = self.by_id.get(reference.id.as_str()) else {
            return Err(reference
                .loc
                .error(format!("no object with id \"{}\"", reference.id)));
        };
        if node.tag != tag {
            return Err(reference.loc.error(format!(
                "id \"{}\" names a <{}>, but a <{tag}> is expected here",
                reference.id, node.tag
            )));
        }
        Ok(node)
    }

    /// The texture `node` takes as its parameter `name` (a nested `<texture name="...">` or a
    /// `<ref name="..." id="...">` to one), if any. Nested objects with a tag in `passed_over`
    /// (a blend's BSDFs), and then references by another name, are left for the caller; any
    /// other nested element is an error.
    fn texture_param(
        &self,
        node: &'a ObjectNode,
        name: &str,
        passed_over: &[&str],
    ) -> Result<Option<TextureDesc>> {
        let mut found = None;
        for child in &node.children {
            let (texture_node, given, loc) = match child {
                Child::Object(object) if passed_over.contains(&object.tag.as_str()) => continue,
                Child::Ref(reference)
                    if !passed_over.is_empty() && reference.name.as_deref() != Some(name) =>
                {
                    continue;
                }
                Child::Object(object) if object.tag == "texture" => {
                    (object, object.name.as_deref(), &object.loc)
                }
                Child::Ref(reference) if reference.name.is_some() => (
                    self.referenced(reference, "texture")?,
                    reference.name.as_deref(),
                    &reference.loc,
                ),
                _ => {
                    return Err(unexpected_child(
                        node,
                        child,
                        &format!("a <texture name=\"{name}\">"),
                    ));
                }
            };
            if given != Some(name) {
                return Err(loc.error(format!(
                    "a texture is supported only as a {} BSDF's \"{name}\"",
                    node.plugin
                )));
            }
            if found.is_some() {
                return Err(loc.error(format!("\"{name}\" is given twice")));
            }
            found = Some(texture(texture_node)?);
        }
        Ok(found)
    }
}

/// Whether a BSDF description lets light through (a dielectric, possibly inside a blend).
fn bsdf_has_transmission(desc: &BsdfDesc) -> bool {
    match desc {
        BsdfDesc::Dielectric { .. }
        | BsdfDesc::RoughDielectric { .. }
        | BsdfDesc::ThinDielectric { .. } => true,
        BsdfDesc::Blend { first, second, .. } => {
            bsdf_has_transmission(first) || bsdf_has_transmission(second)
        }
        BsdfDesc::Checkerboard { even, odd, .. } => {
            bsdf_has_transmission(even) || bsdf_has_transmission(odd)
        }
        BsdfDesc::DiffuseBitmap { base, .. } | BsdfDesc::TexturedBlend { base, .. } => {
            bsdf_has_transmission(base)
        }
        BsdfDesc::Built(bsdf) => bsdf.flags().contains(BsdfFlags::TRANSMISSION),
        _ => false,
    }
}

/// The BSDF `make` gives for the reflectance a texture shows, or for `untextured` without one: a
/// checkerboard of the BSDFs for its two colours, or a bitmap's BSDF with the texture's mean
/// luminance.
fn textured(
    texture: Option<TextureDesc>,
    untextured: glam::Vec3,
    make: impl Fn(glam::Vec3) -> BsdfDesc,
) -> BsdfDesc {
    match texture {
        None => make(untextured),
        Some(TextureDesc::Checkerboard {
            color0,
            color1,
            to_uv,
        }) => BsdfDesc::Checkerboard {
            even: Box::new(make(color0)),
            odd: Box::new(make(color1)),
            to_uv,
        },
        Some(TextureDesc::Bitmap(texture)) => BsdfDesc::DiffuseBitmap {
            base: Box::new(make(glam::Vec3::splat(texture.mean_luminance()))),
            texture,
        },
    }
}

/// `first` and `second` blended by `weight`, or by `weight_texture` when there is one
/// ([`BsdfTable::blend`]); a checkerboard in either is hoisted above the blend, a bitmap weight
/// or a BSDF with a bitmap albedo makes a [`BsdfDesc::TexturedBlend`]. Refused: a textured blend
/// inside, checkerboards beside a textured weight, and bitmap albedos beside a checkerboard.
fn blended(
    node: &ObjectNode,
    parts: [BsdfDesc; 2],
    weight_texture: Option<TextureDesc>,
    weight: f32,
) -> Result<BsdfDesc> {
    let refuse = |what: &str| {
        Err(node
            .loc
            .error(format!("a {} {what} is not supported", node.plugin)))
    };
    if parts
        .iter()
        .any(|b| matches!(b, BsdfDesc::TexturedBlend { .. }))
    {
        return refuse("of a blendbsdf or mask with a bitmap");
    }
    if parts
        .iter()
        .any(|b| matches!(b, BsdfDesc::Built(bsdf) if bsdf.flags().contains(BsdfFlags::AT_SURFACE)))
    {
        return refuse("of a normalmap or bumpmap");
    }
    let has_checkerboard = parts
        .iter()
        .any(|b| matches!(b, BsdfDesc::Checkerboard { .. }));
    // A BSDF with a bitmap albedo takes part as its base, the bitmap kept aside.
    let reflectances = parts.each_ref().map(|b| match b {
        BsdfDesc::DiffuseBitmap { texture, .. } => Some(texture.clone()),
        _ => None,
    });
    let [first, second] = parts.map(|b| match b {
        BsdfDesc::DiffuseBitmap { base, .. } => *base,
        other => other,
    });
    let blend = |[first, second]: [BsdfDesc; 2], weight: f32| BsdfDesc::Blend {
        first: Box::new(first),
        second: Box::new(second),
        weight: weight.clamp(0.0, 1.0),
    };
    let has_bitmap_albedo = reflectances.iter().any(Option::is_some);
    if has_bitmap_albedo
        && (has_checkerboard || matches!(weight_texture, Some(TextureDesc::Checkerboard { .. })))
    {
        return refuse("of a BSDF with a bitmap beside a checkerboard");
    }
    match weight_texture {
        None if has_bitmap_albedo => Ok(BsdfDesc::TexturedBlend {
            base: Box::new(blend([first, second], weight)),
            weight: None,
            reflectances,
        }),
        None => hoist_checkerboard(node, [first, second], |parts| blend(parts, weight)),
        Some(_) if has_checkerboard => {
            refuse("with a textured weight of a BSDF with a checkerboard")
        }
        Some(TextureDesc::Checkerboard {
            color0,
            color1,
            to_uv,
        }) => {
            let mean = |c: glam::Vec3| c.element_sum() / 3.0;
            Ok(BsdfDesc::Checkerboard {
                even: Box::new(blend([first.clone(), second.clone()], mean(color1))),
                odd: Box::new(blend([first, second], mean(color0))),
                to_uv,
            })
        }
        Some(TextureDesc::Bitmap(texture)) => Ok(BsdfDesc::TexturedBlend {
            base: Box::new(blend([first, second], texture.mean_luminance())),
            weight: Some(texture),
            reflectances,
        }),
    }
}

/// Mitsuba's `null`, an invisible surface: light passes straight through it, a delta
/// transmission of weight 1, which a thin slab of equal indices and no reflection is.
fn null_bsdf() -> BsdfDesc {
    BsdfDesc::ThinDielectric {
        int_ior: 1.0,
        ext_ior: 1.0,
        specular_reflectance: glam::Vec3::ZERO,
        specular_transmittance: glam::Vec3::ONE,
    }
}

/// `wrap` applied to `parts`, where a checkerboard among them becomes a checkerboard of the
/// wrapped BSDFs (the parts with its `even`, then its `odd` BSDF), so that the texture is chosen
/// before the wrapper; two different checkerboards in one material are an error.
fn hoist_checkerboard(
    node: &ObjectNode,
    parts: [BsdfDesc; 2],
    wrap: impl Fn([BsdfDesc; 2]) -> BsdfDesc,
) -> Result<BsdfDesc> {
    let checker = parts.iter().find_map(|p| match p {
        BsdfDesc::Checkerboard { to_uv, .. } => Some((p.clone(), *to_uv)),
        _ => None,
    });
    let Some((checker, to_uv)) = checker else {
        return Ok(wrap(parts));
    };
    if parts
        .iter()
        .any(|p| matches!(p, BsdfDesc::Checkerboard { .. }) && *p != checker)
    {
        return Err(node
            .loc
            .error("only one checkerboard texture per material is supported"));
    }
    let side = |part: &BsdfDesc, even: bool| match part {
        BsdfDesc::Checkerboard {
            even: e, odd: o, ..
        } => {
            if even {
                (**e).clone()
            } else {
                (**o).clone()
            }
        }
        other => other.clone(),
    };
    let [a, b] = &parts;
    Ok(BsdfDesc::Checkerboard {
        even: Box::new(wrap([side(a, true), side(b, true)])),
        odd: Box::new(wrap([side(a, false), side(b, false)])),
        to_uv,
    })
}

/// Records every object with an id below `node`.
fn collect_ids<'a>(node: &'a ObjectNode, out: &mut HashMap<&'a str, &'a ObjectNode>) {
    if let Some(id) = &node.id {
        out.insert(id.as_str(), node);
    }
    for child in &node.children {
        if let Child::Object(object) = child {
            collect_ids(object, out);
        }
    }
}

/// A colour parameter as f32 RGB.
fn rgb(
    params: &mut Params,
    name: &'static str,
    kind: ColorKind,
    default: f64,
) -> Result<glam::Vec3> {
    Ok(params.color(name, kind, default)?.as_vec3())
}

/// `eta` and `k`, or the named `material`: `none` (the default) is a perfect mirror (eta = 0,
/// k = 1); `Ag`, `Al`, `Au`, `Cr` and `Cu` are Mitsuba's measured metals in RGB.
fn conductor_ior(params: &mut Params) -> Result<(glam::Vec3, glam::Vec3)> {
    let material = params.string("material")?;
    let has_eta = params.has("eta");
    let has_k = params.has("k");
    if let Some((name, loc)) = material
        && name != "none"
    {
        if has_eta || has_k {
            return Err(loc.error("give either \"eta\"/\"k\" or \"material\", not both"));
        }
        let (eta, k) = lookup_conductor(name).ok_or_else(|| {
            let names: Vec<&str> = CONDUCTORS.iter().map(|(n, _, _)| *n).collect();
            loc.error(format!(
                "unsupported conductor material \"{name}\" (supported: none, {}; or give eta and k as <rgb>)",
                names.join(", ")
            ))
        })?;
        return Ok((glam::Vec3::from_array(eta), glam::Vec3::from_array(k)));
    }
    let eta = params.color("eta", ColorKind::Unbounded, 0.0)?;
    let k = params.color("k", ColorKind::Unbounded, 1.0)?;
    Ok((eta.as_vec3(), k.as_vec3()))
}

/// The microfacet `distribution` (default Beckmann, as in Mitsuba).
fn distribution(params: &mut Params) -> Result<MicrofacetDistribution> {
    match params.string("distribution")? {
        None => Ok(MicrofacetDistribution::Beckmann),
        Some((name, loc)) => match name.to_ascii_lowercase().as_str() {
            "beckmann" => Ok(MicrofacetDistribution::Beckmann),
            "ggx" => Ok(MicrofacetDistribution::Ggx),
            _ => Err(loc.error(format!(
                "unknown distribution \"{name}\" (supported: beckmann, ggx)"
            ))),
        },
    }
}

/// Fails, naming the parameter, when a rough BSDF's roughness is given by a nested texture
/// (Mitsuba's textured `alpha`, `alpha_u` or `alpha_v`), which Strata does not support.
fn refuse_textured_roughness(node: &ObjectNode) -> Result<()> {
    for child in &node.children {
        if let Child::Object(texture) = child
            && let Some(name) = texture.name.as_deref()
            && ["alpha", "alpha_u", "alpha_v"].contains(&name)
        {
            return Err(texture.loc.error(format!(
                "textured roughness (a texture for \"{name}\") is not supported: give a <float>"
            )));
        }
    }
    Ok(())
}

/// The isotropic roughness of a BSDF that has no other (Mitsuba's `roughplastic`): `alpha`
/// (default 0.1), or equal `alpha_u` and `alpha_v`.
fn alpha(params: &mut Params) -> Result<f32> {
    let Roughness { u, v } = roughness(params)?;
    if u != v {
        return Err(params
            .loc_of("alpha_u")
            .error("this BSDF's roughness is isotropic: alpha_u and alpha_v must be equal"));
    }
    Ok(u)
}

/// The roughness: `alpha` (default 0.1), or `alpha_u` along ∂p/∂u and `alpha_v` across it,
/// each positive.
fn roughness(params: &mut Params) -> Result<Roughness> {
    // Mitsuba's sample_visible only changes the sampling strategy, not the image.
    params.boolean_or("sample_visible", true)?;
    let alpha = params.float("alpha")?;
    let alpha_u = params.float("alpha_u")?;
    let alpha_v = params.float("alpha_v")?;
    let (u, v) = match (alpha, alpha_u, alpha_v) {
        (Some(a), None, None) => (a, a),
        (None, None, None) => (0.1, 0.1),
        (None, Some(u), Some(v)) => (u, v),
        (None, _, _) => {
            return Err(params
                .loc()
                .error("give both \"alpha_u\" and \"alpha_v\", or \"alpha\""));
        }
        (Some(_), _, _) => {
            return Err(params
                .loc_of("alpha")
                .error("give either \"alpha\" or \"alpha_u\"/\"alpha_v\", not both"));
        }
    };
    for (value, name) in [(u, "alpha_u"), (v, "alpha_v")] {
        if value <= 0.0 {
            let name = if alpha.is_some() { "alpha" } else { name };
            return Err(params
                .loc_of(name)
                .error(format!("roughness must be positive, got {name} = {value}")));
        }
    }
    Ok(Roughness {
        u: u as f32,
        v: v as f32,
    })
}

/// A coated material's `diffuse_reflectance` (default 0.5), `specular_reflectance` (default 1)
/// and `nonlinear` (default false), as `plastic` and `roughplastic` read them.
fn coating(params: &mut Params) -> Result<(glam::Vec3, glam::Vec3, bool)> {
    Ok((
        rgb(params, "diffuse_reflectance", ColorKind::Reflectance, 0.5)?,
        specular_reflectance(params)?,
        params.boolean_or("nonlinear", false)?,
    ))
}

/// Mitsuba's `specular_reflectance` multiplier (default 1).
fn specular_reflectance(params: &mut Params) -> Result<glam::Vec3> {
    rgb(params, "specular_reflectance", ColorKind::Reflectance, 1.0)
}

/// Mitsuba's `specular_transmittance` multiplier (default 1).
fn specular_transmittance(params: &mut Params) -> Result<glam::Vec3> {
    rgb(
        params,
        "specular_transmittance",
        ColorKind::Reflectance,
        1.0,
    )
}

/// An interface's `int_ior` (default `int_default`) and `ext_ior` (default air), which must
/// differ as Mitsuba requires of its solid and rough dielectrics and rough plastic.
fn distinct_iors(params: &mut Params, int_default: f64) -> Result<(f32, f32)> {
    let int_ior = ior(params, "int_ior", int_default)?;
    let ext_ior = ior(params, "ext_ior", 1.000277)?;
    if int_ior == ext_ior {
        return Err(params
            .loc()
            .error("the interior and exterior indices of refraction must differ"));
    }
    Ok((int_ior as f32, ext_ior as f32))
}

/// An index of refraction given as a number or as one of Mitsuba's material names.
fn ior(params: &mut Params, name: &'static str, default: f64) -> Result<f64> {
    let loc = params.loc_of(name);
    let value = match params.string(name) {
        Ok(Some((material, loc))) => lookup_ior(material).ok_or_else(|| {
            loc.error(format!(
                "unknown material \"{material}\" for {name} (supported: a number or one of {})",
                ior_names()
            ))
        })?,
        Ok(None) => default,
        Err(_) => params.float(name)?.unwrap_or(default),
    };
    if value <= 0.0 {
        return Err(loc.error(format!("{name} must be positive, got {value}")));
    }
    Ok(value)
}
