//! Typed access to a plugin's properties that remembers which ones were read, so that any
//! parameter a plugin does not understand becomes an error naming what it does understand.

use glam::{DMat4, DVec3};

use crate::error::{Loc, Result};
use crate::spectrum::{SpectrumRole, spectrum_to_srgb, xyz_to_srgb};
use crate::xml::tree::{ObjectNode, Prop, Value};

/// How a colour parameter is interpreted (Mitsuba's texture kinds in its RGB variants).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ColorKind {
    /// A reflectance: every channel in [0, 1].
    Reflectance,
    /// An unbounded non-negative quantity such as a conductor's `eta` or `k`.
    Unbounded,
    /// Emitted radiance or intensity: non-negative; a uniform `<spectrum>` becomes
    /// `value × xyz_to_srgb(1, 1, 1)` as in Mitsuba's RGB variants.
    Emission,
}

/// Where a transform parameter puts something: fixed, or moving over time.
#[derive(Debug, Clone)]
pub(crate) enum Placement {
    /// A `<transform>`.
    Fixed(DMat4),
    /// An `<animation>` (Strata's extension for motion blur).
    Animated(geometry::AnimatedTransform),
}

/// The properties of one plugin object being interpreted.
pub(crate) struct Params<'a> {
    node: &'a ObjectNode,
    used: Vec<bool>,
    supported: Vec<&'static str>,
}

impl<'a> Params<'a> {
    /// Starts reading the properties of `node`.
    pub fn new(node: &'a ObjectNode) -> Self {
        Self {
            node,
            used: vec![false; node.props.len()],
            supported: Vec::new(),
        }
    }

    /// The location of the object itself.
    pub fn loc(&self) -> &'a Loc {
        &self.node.loc
    }

    /// Registers `name` as supported and returns its property, marking it read.
    fn find(&mut self, name: &'static str) -> Option<&'a Prop> {
        if !self.supported.contains(&name) {
            self.supported.push(name);
        }
        let index = self.node.props.iter().position(|p| p.name == name)?;
        self.used[index] = true;
        Some(&self.node.props[index])
    }

    /// True when the object sets `name` (registers it as supported).
    pub fn has(&mut self, name: &'static str) -> bool {
        self.find(name).is_some()
    }

    /// The location of property `name`, or of the object when it is absent.
    pub fn loc_of(&mut self, name: &'static str) -> &'a Loc {
        match self.find(name) {
            Some(prop) => &prop.loc,
            None => &self.node.loc,
        }
    }

    /// Accepts `name` as a parameter that does not change what Strata renders.
    pub fn ignore(&mut self, name: &'static str) {
        self.find(name);
    }

    /// A float parameter (an `<integer>` is accepted too).
    pub fn float(&mut self, name: &'static str) -> Result<Option<f64>> {
        match self.find(name) {
            None => Ok(None),
            Some(prop) => match prop.value {
                Value::Float(v) => Ok(Some(v)),
                Value::Integer(v) => Ok(Some(v as f64)),
                _ => Err(wrong_type(prop, "float")),
            },
        }
    }

    /// A float parameter with a default.
    pub fn float_or(&mut self, name: &'static str, default: f64) -> Result<f64> {
        Ok(self.float(name)?.unwrap_or(default))
    }

    /// An integer parameter.
    pub fn integer(&mut self, name: &'static str) -> Result<Option<(i64, &'a Loc)>> {
        match self.find(name) {
            None => Ok(None),
            Some(prop) => match prop.value {
                Value::Integer(v) => Ok(Some((v, &prop.loc))),
                _ => Err(wrong_type(prop, "integer")),
            },
        }
    }

    /// An integer parameter with a default, required to lie in `[min, max]`.
    pub fn integer_in(
        &mut self,
        name: &'static str,
        default: i64,
        min: i64,
        max: i64,
    ) -> Result<i64> {
        match self.integer(name)? {
            None => Ok(default),
            Some((v, _)) if (min..=max).contains(&v) => Ok(v),
            Some((v, loc)) => {
                Err(loc.error(format!("\"{name}\" must lie in [{min}, {max}], got {v}")))
            }
        }
    }

    /// A boolean parameter with a default.
    pub fn boolean_or(&mut self, name: &'static str, default: bool) -> Result<bool> {
        match self.find(name) {
            None => Ok(default),
            Some(prop) => match prop.value {
                Value::Boolean(v) => Ok(v),
                _ => Err(wrong_type(prop, "boolean")),
            },
        }
    }

    /// A string parameter with the location of its element.
    pub fn string(&mut self, name: &'static str) -> Result<Option<(&'a str, &'a Loc)>> {
        match self.find(name) {
            None => Ok(None),
            Some(prop) => match &prop.value {
                Value::String(v) => Ok(Some((v.as_str(), &prop.loc))),
                _ => Err(wrong_type(prop, "string")),
            },
        }
    }

    /// A point parameter (a `<vector>` is accepted too).
    pub fn point(&mut self, name: &'static str) -> Result<Option<DVec3>> {
        match self.find(name) {
            None => Ok(None),
            Some(prop) => match prop.value {
                Value::Point(v) | Value::Vector(v) => Ok(Some(v)),
                _ => Err(wrong_type(prop, "point")),
            },
        }
    }

    /// A transform parameter of something that cannot move.
    pub fn transform(&mut self, name: &'static str) -> Result<Option<DMat4>> {
        match self.find(name) {
            None => Ok(None),
            Some(prop) => match prop.value {
                Value::Transform(m) => Ok(Some(m)),
                Value::Animation(ref animation) => {
                    let (first, last) = animation.time_range();
                    Err(prop.loc.error(format!(
                        "\"{}\" is animated (times {first} to {last}), but only a shape can \
                         move (motion blur); give a <transform>",
                        prop.name
                    )))
                }
                _ => Err(wrong_type(prop, "transform")),
            },
        }
    }

    /// A transform parameter that may move: a `<transform>` or an `<animation>`.
    pub fn placement(&mut self, name: &'static str) -> Result<Option<Placement>> {
        match self.find(name) {
            None => Ok(None),
            Some(prop) => match prop.value {
                Value::Transform(m) => Ok(Some(Placement::Fixed(m))),
                Value::Animation(ref animation) => Ok(Some(Placement::Animated(animation.clone()))),
                _ => Err(wrong_type(prop, "transform")),
            },
        }
    }

    /// A colour given as `<rgb>`, `<float>`/`<integer>` (grey) or a `<spectrum>` (uniform, or
    /// wavelength–value pairs integrated to sRGB as Mitsuba's RGB variants do), validated for its
    /// `kind`; `default` is a grey level used when the parameter is absent.
    pub fn color(&mut self, name: &'static str, kind: ColorKind, default: f64) -> Result<DVec3> {
        let Some(prop) = self.find(name) else {
            return Ok(DVec3::splat(default));
        };
        let rgb = match prop.value {
            Value::Rgb(v) => v,
            Value::Float(v) => DVec3::splat(v),
            Value::Integer(v) => DVec3::splat(v as f64),
            Value::Spectrum(v) if kind == ColorKind::Emission => v * xyz_to_srgb(DVec3::ONE),
            Value::Spectrum(v) => DVec3::splat(v),
            Value::SpectrumPairs(ref pairs) => spectrum_to_srgb(
                pairs,
                match kind {
                    ColorKind::Reflectance => SpectrumRole::Reflectance,
                    ColorKind::Unbounded => SpectrumRole::Unbounded,
                    ColorKind::Emission => SpectrumRole::Emission,
                },
            ),
            _ => return Err(wrong_type(prop, "rgb")),
        };
        if rgb.min_element() < 0.0 {
            return Err(prop
                .loc
                .error(format!("\"{name}\" must not be negative, got {rgb}")));
        }
        if kind == ColorKind::Reflectance && rgb.max_element() > 1.0 {
            return Err(prop.loc.error(format!(
                "reflectance \"{name}\" must lie in [0, 1], got {rgb}"
            )));
        }
        Ok(rgb)
    }

    /// Fails on the first property that no getter asked for, listing the supported names.
    pub fn finish(self) -> Result<()> {
        for (prop, used) in self.node.props.iter().zip(&self.used) {
            if !used {
                let supported = if self.supported.is_empty() {
                    "none".to_string()
                } else {
                    self.supported.join(", ")
                };
                return Err(prop.loc.error(format!(
                    "unsupported parameter \"{}\" for {} (supported: {supported})",
                    prop.name, self.node.loc.element
                )));
            }
        }
        Ok(())
    }
}

/// The error for a property of the wrong kind.
fn wrong_type(prop: &Prop, expected: &str) -> crate::error::LoadError {
    prop.loc.error(format!(
        "parameter \"{}\" must be given as <{expected}>, not <{}>",
        prop.name,
        prop.value.tag()
    ))
}
