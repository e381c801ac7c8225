//! Rejection kinds: an error reduced to what kind of error it is (a variant, a TOML path with
//! its indices blanked, a message up to its first quoted part), so the fuzzer can count them
//! and grow its pool with inputs that reach a new one.

use study::ScenarioError;

/// `text` up to its first quoted part, digits blanked, cut short: an error kind, not an
/// instance.
pub fn normalize(text: &str) -> String {
    let mut out = String::new();
    for c in text.chars().take_while(|c| !matches!(c, '`' | '"' | '\'')) {
        if !c.is_ascii_digit() {
            out.push(c);
        } else if !out.ends_with('#') {
            out.push('#');
        }
        if out.len() >= 60 {
            break;
        }
    }
    out
}

/// The variant name of an error, from its `Debug` form.
pub fn variant(e: &impl std::fmt::Debug) -> String {
    let d = format!("{e:?}");
    d.split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .next()
        .unwrap_or("")
        .to_owned()
}

pub fn scenario_kind(e: &ScenarioError) -> String {
    match e {
        ScenarioError::Io { .. } => "io".to_owned(),
        ScenarioError::Syntax { message, .. } => format!("syntax: {}", normalize(message)),
        ScenarioError::Field { field, .. } => format!("field {}", normalize(field)),
        ScenarioError::Map { field, source, .. } => format!("{field}: {}", raster_kind(source)),
        ScenarioError::Zones { source, .. } => format!("map.zones: {}", variant(source)),
        // The loader checks every field first: the simulator refusing what it built is a bug,
        // reported as a failure with its input.
        ScenarioError::Settings { .. } => panic!("the loader let through a campaign: {e}"),
    }
}

pub fn raster_kind(e: &maps::RasterError) -> String {
    match e {
        maps::RasterError::Decode { detail, .. } => format!("Decode({})", normalize(detail)),
        e => variant(e),
    }
}
