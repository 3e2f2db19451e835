//! Parsing of the textual values found in attributes: numbers, booleans and number lists.

use glam::DVec3;

use crate::error::{Loc, Result};

/// Splits a value list at commas and whitespace, dropping empty pieces (Mitsuba's `tokenize`).
pub(crate) fn tokenize(text: &str) -> Vec<&str> {
    text.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .collect()
}

/// Parses a finite floating-point number; NaN and infinities are errors.
pub(crate) fn parse_float(text: &str, loc: &Loc) -> Result<f64> {
    let trimmed = text.trim();
    match trimmed.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(loc.error(format!(
            "value \"{trimmed}\" is not a finite number (NaN and infinity are not allowed)"
        ))),
        Err(_) => Err(loc.error(format!("could not parse \"{trimmed}\" as a number"))),
    }
}

/// Parses a decimal integer.
pub(crate) fn parse_integer(text: &str, loc: &Loc) -> Result<i64> {
    let trimmed = text.trim();
    trimmed
        .parse::<i64>()
        .map_err(|_| loc.error(format!("could not parse \"{trimmed}\" as an integer")))
}

/// Parses `true` or `false` (any letter case), as Mitsuba does.
pub(crate) fn parse_boolean(text: &str, loc: &Loc) -> Result<bool> {
    let trimmed = text.trim();
    if trimmed.eq_ignore_ascii_case("true") {
        Ok(true)
    } else if trimmed.eq_ignore_ascii_case("false") {
        Ok(false)
    } else {
        Err(loc.error(format!(
            "could not parse \"{trimmed}\" as a boolean (expected \"true\" or \"false\")"
        )))
    }
}

/// Parses a list of exactly `n` finite numbers.
pub(crate) fn parse_floats(text: &str, n: usize, loc: &Loc) -> Result<Vec<f64>> {
    let tokens = tokenize(text);
    if tokens.len() != n {
        return Err(loc.error(format!(
            "expected {n} numbers, got {} in \"{text}\"",
            tokens.len()
        )));
    }
    tokens.iter().map(|t| parse_float(t, loc)).collect()
}

/// Most wavelength–value pairs a spectrum may list.
const MAX_SPECTRUM_PAIRS: usize = 10_000;

/// Parses a spectrum given as `wavelength:value` pairs separated by commas or whitespace
/// (Mitsuba's `<spectrum value="400:0.5, 500:0.7"/>`): at least two, wavelengths positive and
/// strictly increasing, values finite.
pub(crate) fn parse_spectrum_pairs(text: &str, loc: &Loc) -> Result<Vec<(f64, f64)>> {
    let tokens = tokenize(text);
    if tokens.len() > MAX_SPECTRUM_PAIRS {
        return Err(loc.error(format!(
            "a spectrum may list at most {MAX_SPECTRUM_PAIRS} wavelength:value pairs, got {}",
            tokens.len()
        )));
    }
    let mut pairs: Vec<(f64, f64)> = Vec::with_capacity(tokens.len());
    for token in tokens {
        let Some((wavelength, value)) = token.split_once(':') else {
            return Err(loc.error(format!(
                "\"{token}\" is not a wavelength:value pair (e.g. \"400:0.5\")"
            )));
        };
        let (wavelength, value) = (parse_float(wavelength, loc)?, parse_float(value, loc)?);
        if wavelength <= 0.0 {
            return Err(loc.error(format!("wavelength {wavelength} nm is not positive")));
        }
        if let Some(&(previous, _)) = pairs.last()
            && wavelength <= previous
        {
            return Err(loc.error(format!(
                "wavelengths must increase: {wavelength} nm follows {previous} nm"
            )));
        }
        pairs.push((wavelength, value));
    }
    if pairs.len() < 2 {
        return Err(
            loc.error("a spectrum given by wavelengths needs at least two wavelength:value pairs")
        );
    }
    Ok(pairs)
}

/// Parses one number (broadcast to all three components) or three numbers.
pub(crate) fn parse_vec3_or_scalar(text: &str, loc: &Loc) -> Result<DVec3> {
    let tokens = tokenize(text);
    match tokens.as_slice() {
        [v] => Ok(DVec3::splat(parse_float(v, loc)?)),
        [x, y, z] => Ok(DVec3::new(
            parse_float(x, loc)?,
            parse_float(y, loc)?,
            parse_float(z, loc)?,
        )),
        _ => Err(loc.error(format!(
            "expected 1 or 3 numbers, got {} in \"{text}\"",
            tokens.len()
        ))),
    }
}

/// Parses exactly three numbers.
pub(crate) fn parse_vec3(text: &str, loc: &Loc) -> Result<DVec3> {
    let v = parse_floats(text, 3, loc)?;
    Ok(DVec3::new(v[0], v[1], v[2]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn loc() -> Loc {
        Loc::file_only(Path::new("t.xml"))
    }

    #[test]
    fn tokenize_accepts_commas_and_spaces() {
        assert_eq!(tokenize(" 1, 2  3,,4\t5\n"), vec!["1", "2", "3", "4", "5"]);
    }

    #[test]
    fn floats_reject_nan_and_infinity() {
        assert!(parse_float("nan", &loc()).is_err());
        assert!(parse_float("inf", &loc()).is_err());
        assert!(parse_float("-infinity", &loc()).is_err());
        assert!(parse_float("1e400", &loc()).is_err());
        assert_eq!(parse_float(" -2.5e1 ", &loc()).unwrap(), -25.0);
    }

    #[test]
    fn vec3_broadcasts_single_value() {
        assert_eq!(
            parse_vec3_or_scalar("0.5", &loc()).unwrap(),
            DVec3::splat(0.5)
        );
        assert_eq!(
            parse_vec3_or_scalar("1 2,3", &loc()).unwrap(),
            DVec3::new(1.0, 2.0, 3.0)
        );
        assert!(parse_vec3_or_scalar("1 2", &loc()).is_err());
    }

    #[test]
    fn booleans_are_case_insensitive() {
        assert!(parse_boolean("TRUE", &loc()).unwrap());
        assert!(!parse_boolean("False", &loc()).unwrap());
        assert!(parse_boolean("yes", &loc()).is_err());
    }
}
