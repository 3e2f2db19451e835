//! An element's attributes after `$name` substitution, with Mitsuba's attribute checks.

use crate::error::{Loc, Result};

/// Attribute name/value pairs in document order, values already substituted.
#[derive(Debug, Clone, Default)]
pub(crate) struct Attrs(Vec<(String, String)>);

impl Attrs {
    /// Builds attributes from pairs.
    #[cfg(test)]
    pub fn from_pairs(pairs: &[(&str, &str)]) -> Self {
        Self(
            pairs
                .iter()
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .collect(),
        )
    }

    /// Appends one attribute.
    pub fn push(&mut self, name: String, value: String) {
        self.0.push((name, value));
    }

    /// The value of attribute `name`, if present.
    pub fn get(&self, name: &str) -> Option<&str> {
        self.0
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    /// Fails on any attribute not in `allowed` and on any `required` attribute that is missing.
    pub fn check(&self, allowed: &[&str], required: &[&str], loc: &Loc) -> Result<()> {
        for (name, _) in &self.0 {
            if !allowed.contains(&name.as_str()) {
                return Err(loc.error(format!(
                    "unexpected attribute \"{name}\" (allowed: {})",
                    allowed.join(", ")
                )));
            }
        }
        for name in required {
            if self.get(name).is_none() {
                return Err(loc.error(format!("missing required attribute \"{name}\"")));
            }
        }
        Ok(())
    }
}
