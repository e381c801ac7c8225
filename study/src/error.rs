//! Errors in scenario files: every one names the file, the field and what was expected.

use std::path::PathBuf;

/// Why a scenario could not be loaded. Displayed as one line:
/// `FILE: FIELD: expected WHAT, got VALUE`.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read: missing, not a regular file (a FIFO, a device), larger
    /// than [`maps::input_file::MAX_TEXT_FILE_BYTES`], or not UTF-8.
    #[error("{}: {error}", path.display())]
    Io {
        /// The scenario file.
        path: PathBuf,
        /// Why (part of the message, so not also a `source`).
        error: maps::input_file::InputFileError,
    },
    /// The TOML did not parse or did not match the expected format.
    #[error("{}: line {line}, column {column}{}: {message}", path.display(), text.as_deref().map_or(String::new(), |t| format!(" (`{t}`)")))]
    Syntax {
        /// The file.
        path: PathBuf,
        /// 1-based line of the offending text.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The offending line, trimmed and escaped; `None` when the file does not read as
        /// one of solsim's ([`quotes_toml_excerpt`]): its text is not quoted.
        text: Option<String>,
        /// What the parser expected.
        message: String,
    },
    /// A field has a value outside what is allowed.
    #[error("{}: {field}: expected {expected}, got {got}", path.display())]
    Field {
        /// The scenario file.
        path: PathBuf,
        /// TOML path of the field, e.g. `sols[3].historic_distance_m`.
        field: String,
        /// What is allowed.
        expected: String,
        /// What the file holds.
        got: String,
    },
    /// A map raster referenced by the scenario could not be loaded.
    #[error("{}: {field}: {source}", path.display())]
    Map {
        /// The scenario file.
        path: PathBuf,
        /// The field naming the raster.
        field: String,
        /// What went wrong with the raster.
        source: Box<maps::RasterError>,
    },
    /// The settings built from a valid file failed the simulator's own checks (a bug in the
    /// loader if it ever shows: every field is checked before).
    #[error("{}: {source}", path.display())]
    Settings {
        /// The scenario file.
        path: PathBuf,
        /// What the simulator refused.
        source: sim::SettingsError,
    },
    /// The zones file referenced by the scenario could not be loaded.
    #[error("{}: map.zones: {source}", path.display())]
    Zones {
        /// The scenario file.
        path: PathBuf,
        /// What went wrong with the zones.
        source: Box<maps::ZoneError>,
    },
}

impl ScenarioError {
    /// A [`ScenarioError::Field`] error.
    pub fn field(
        path: &std::path::Path,
        field: impl Into<String>,
        expected: impl Into<String>,
        got: impl std::fmt::Display,
    ) -> Self {
        ScenarioError::Field {
            path: path.to_path_buf(),
            field: excerpt(&field.into(), MAX_EXCERPT_CHARS),
            // An expectation may quote another field's value (`at most battery_capacity_wh =
            // 1e300 Wh`): numbers print readably there too.
            expected: readable_numbers(&Into::<String>::into(expected)),
            got: excerpt(&readable_value(&got.to_string()), MAX_EXCERPT_CHARS),
        }
    }

    /// Turn a TOML parse error into a one-line [`ScenarioError::Syntax`]. `known_keys` are
    /// the top-level keys of the expected format ([`toml_keys`]): unless the file reads as
    /// that format up to the offending line ([`quotes_toml_excerpt`]), nothing of its text
    /// is quoted — `solsim validate /etc/shadow` says where it stopped and what it expected,
    /// not what the file holds.
    #[must_use]
    pub fn from_toml(
        path: &std::path::Path,
        text: &str,
        err: &toml::de::Error,
        known_keys: &[&str],
    ) -> Self {
        let offset = floor_char_boundary(text, err.span().map_or(0, |s| s.start));
        let before = &text[..offset];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let column = text[line_start..offset].chars().count() + 1;
        let parser_says = err
            .message()
            .lines()
            .next()
            .unwrap_or("invalid TOML")
            .trim();
        let (text, message) = if quotes_toml_excerpt(text, line_start, known_keys) {
            let line_text = text[line_start..].lines().next().unwrap_or("").trim();
            // A misspelt key or name: the closest known one first, then the format's names
            // whole (cutting the message at MAX_EXCERPT_CHARS lost them).
            let message = maps::names::unknown_name_message(parser_says, MAX_EXCERPT_CHARS)
                .unwrap_or_else(|| excerpt(&readable_numbers(parser_says), MAX_EXCERPT_CHARS));
            (Some(excerpt(line_text, MAX_EXCERPT_CHARS)), message)
        } else {
            let keys = match known_keys {
                [] => "this kind of file's".to_owned(),
                keys => keys
                    .iter()
                    .take(4)
                    .map(|k| format!("`{k}`"))
                    .collect::<Vec<_>>()
                    .join(", "),
            };
            let why = if quotes_only_punctuation(parser_says) {
                format!(" ({})", excerpt(parser_says, MAX_EXCERPT_CHARS))
            } else {
                String::new()
            };
            let message = format!(
                "expected a TOML file with such keys as {keys}, got one that does not read as such{why}; its text is not quoted"
            );
            (None, message)
        };
        ScenarioError::Syntax {
            path: path.to_path_buf(),
            line,
            column,
            text,
            message,
        }
    }
}

/// The largest char boundary of `text` at or before `offset`.
fn floor_char_boundary(text: &str, offset: usize) -> usize {
    let mut i = offset.min(text.len());
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// Whether an error may quote a TOML file's offending line (its start at byte `line_start`):
/// the rule that keeps solsim from printing files that are not its own (`/etc/shadow`,
/// `/proc/self/environ`, a `.env` file, a credentials file) when one is given by mistake or by
/// someone who controls the argument but cannot read the file.
///
/// The line is quoted only if the file is TOML holding at least one top-level key of the
/// expected format (`known_keys`) as far as it parses: the whole text when it parses (the
/// error is about types or fields: a missing `map`, a string for a number), else the text
/// before the offending line. A file of another kind fails on its first line (nothing before
/// it, so no key), or parses for a while but with keys of its own (`PRETTY_NAME = "…"`,
/// `[registry]`, `password = "…"`): none is quoted. The cost is a scenario whose syntax error
/// sits above its first known key: it gets the line and column without the quote. Keys
/// rather than "not the first line": a `.env` file whose first line happens to be valid TOML
/// must not have its second line printed.
#[must_use]
pub fn quotes_toml_excerpt(text: &str, line_start: usize, known_keys: &[&str]) -> bool {
    let has_known_key = |t: toml::Table| t.keys().any(|k| known_keys.contains(&k.as_str()));
    match toml::from_str::<toml::Table>(text) {
        Ok(table) => has_known_key(table),
        Err(_) => text
            .get(..line_start)
            .and_then(|before| toml::from_str::<toml::Table>(before).ok())
            .is_some_and(has_known_key),
    }
}

/// Whether the parser's message quotes nothing but punctuation (`` expected `=` ``,
/// "invalid key"): the TOML grammar's own words, which may be shown for any file. Messages
/// that quote the file (`` unknown field `x` ``, `invalid type: string "x"`) may not.
fn quotes_only_punctuation(message: &str) -> bool {
    !message.contains(['"', '\''])
        && message
            .split('`')
            .skip(1)
            .step_by(2)
            .all(|quoted| quoted.len() <= 3 && quoted.chars().all(|c| c.is_ascii_punctuation()))
}

/// The top-level keys of the TOML format `T`: the fields its `Deserialize` implementation
/// names (a struct's fields, in declaration order), read by asking it to deserialize from a
/// deserializer that only records them. Empty for a type that is not a struct.
#[must_use]
pub fn toml_keys<T: serde::de::DeserializeOwned>() -> &'static [&'static str] {
    struct Fields(Option<&'static [&'static str]>);
    impl<'de> serde::Deserializer<'de> for &mut Fields {
        type Error = serde::de::value::Error;
        fn deserialize_any<V: serde::de::Visitor<'de>>(
            self,
            _: V,
        ) -> Result<V::Value, Self::Error> {
            Err(serde::de::Error::custom("fields only"))
        }
        fn deserialize_struct<V: serde::de::Visitor<'de>>(
            self,
            _name: &'static str,
            fields: &'static [&'static str],
            _visitor: V,
        ) -> Result<V::Value, Self::Error> {
            self.0 = Some(fields);
            Err(serde::de::Error::custom("fields only"))
        }
        serde::forward_to_deserialize_any! {
            bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes
            byte_buf option unit unit_struct newtype_struct seq tuple tuple_struct map enum
            identifier ignored_any
        }
    }
    let mut fields = Fields(None);
    let _ = T::deserialize(&mut fields);
    fields.0.unwrap_or(&[])
}

/// Longest excerpt of a file (an offending line, a value, a field) quoted in a message,
/// characters: a message stays one readable line whatever the input holds.
pub const MAX_EXCERPT_CHARS: usize = 120;

pub use maps::input_file::excerpt;

/// A number as a person reads it: `1e300` rather than 301 digits, `1.5e-9` rather than a run
/// of zeros, an integer as its digits (`2147483647`, not `2.147483647e9`); anything that is not
/// a plain number is returned unchanged.
#[must_use]
pub fn readable_value(text: &str) -> String {
    let plain = !text.is_empty()
        && text
            .chars()
            .all(|c| c.is_ascii_digit() || matches!(c, '-' | '.' | '+' | 'e' | 'E'));
    if !plain {
        return text.to_string();
    }
    let digits = text.trim_start_matches(['-', '+']);
    if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
        return readable_integer(text);
    }
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() && v != 0.0 && (v.abs() >= 1e15 || v.abs() < 1e-4) => {
            format!("{v:e}")
        }
        _ => text.to_string(),
    }
}

/// An integer's digits (optionally signed) as a person reads them: as they are (`2147483647`,
/// an exact `u64`), unless they are a float's exact spelling of 1e9 or more that scientific
/// notation says shorter (`1e9`, and `1e300` rather than 301 digits).
fn readable_integer(text: &str) -> String {
    let unsigned = text.trim_start_matches('+');
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() && v.abs() >= 1e9 && format!("{v}") == unsigned => {
            let scientific = format!("{v:e}");
            if scientific.len() < unsigned.len() {
                scientific
            } else {
                text.to_string()
            }
        }
        _ => text.to_string(),
    }
}

/// `text` with every run of more than 15 digits that spells a float in full (a number no one
/// reads: `1e300` spelled out by a parser or a `{}` format) rewritten as `1e300`. Integers a
/// person wrote, up to `u64::MAX`, stay as they are.
#[must_use]
pub fn readable_numbers(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(start) = rest.find(|c: char| c.is_ascii_digit()) {
        out.push_str(&rest[..start]);
        let run = &rest[start..];
        let end = run
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(run.len());
        let number = &run[..end];
        let digits = number.chars().filter(char::is_ascii_digit).count();
        let integer = number.trim_end_matches('.');
        match number.parse::<f64>() {
            Ok(_) if digits > 15 && !integer.contains('.') => {
                out.push_str(&readable_integer(integer));
                out.push_str(&number[integer.len()..]);
            }
            Ok(v) if digits > 15 => out.push_str(&format!("{v:e}")),
            _ => out.push_str(number),
        }
        rest = &run[end..];
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn excerpts_are_capped_on_character_boundaries() {
        assert_eq!(excerpt("short", 80), "short");
        let long = "é".repeat(1000);
        let e = excerpt(&long, 80);
        assert_eq!(e.chars().count(), 80);
        assert!(e.ends_with('…'));
    }

    #[derive(Debug, serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Format {
        name: String,
        seed: u64,
    }

    fn syntax(text: &str) -> String {
        let path = std::path::Path::new("f.toml");
        let e = toml::from_str::<Format>(text).expect_err("invalid");
        ScenarioError::from_toml(path, text, &e, toml_keys::<Format>()).to_string()
    }

    #[test]
    fn the_expected_keys_come_from_the_format() {
        assert_eq!(toml_keys::<Format>(), ["name", "seed"]);
        assert!(toml_keys::<u64>().is_empty());
    }

    #[test]
    fn only_files_that_read_as_the_format_are_quoted() {
        // A solsim file: the line is quoted.
        assert_eq!(
            syntax("# c\nname = \"x\"\nseed = \"s\"\n"),
            "f.toml: line 3, column 8 (`seed = \"s\"`): invalid type: string \"s\", expected u64"
        );
        // Not one: where and what was expected, nothing of the file.
        let shadow = "root:$6$secret:19000:0:99999:7:::\n";
        let e = syntax(shadow);
        assert_eq!(
            e,
            "f.toml: line 1, column 34: expected a TOML file with such keys as `name`, `seed`, got one that does not read as such (key with no value, expected `=`); its text is not quoted"
        );
        let env = "HOME=/root\0TOKEN=abc123\0";
        assert!(!syntax(env).contains("abc123"), "{}", syntax(env));
        // Valid TOML up to the line, but none of the format's keys: not quoted either.
        let dotenv = "PRETTY_NAME = \"x\"\nSECRET=xyz\n";
        assert!(!syntax(dotenv).contains("xyz"), "{}", syntax(dotenv));
        // A message that quotes the file is left out too.
        let e = syntax("password = \"hunter2\"\n");
        assert!(!e.contains("password") && !e.contains("hunter2"), "{e}");
        // An error about the whole document (a missing field) in a file that is TOML with a
        // known key: quoted.
        assert_eq!(
            syntax("name = \"x\"\n"),
            "f.toml: line 1, column 1 (`name = \"x\"`): missing field `seed`"
        );
        // The first key misspelled, the rest of the file solsim's: quoted.
        assert!(
            syntax("nmae = \"x\"\nseed = 1\n")
                .contains("unknown field `nmae` (did you mean `name`?), expected `name` or `seed`")
        );
    }

    #[test]
    fn long_digit_runs_are_shortened() {
        let spelled = format!("floating point `{}`, expected u64", 1e300_f64);
        assert_eq!(
            readable_numbers(&spelled),
            "floating point `1e300`, expected u64"
        );
        assert_eq!(readable_numbers("line 12, column 3"), "line 12, column 3");
        assert_eq!(
            readable_numbers("got 18446744073709551615."),
            "got 18446744073709551615."
        );
        assert_eq!(
            readable_numbers(&format!("length_m = {} m", 1e300_f64)),
            "length_m = 1e300 m"
        );
    }

    #[test]
    fn numbers_print_readably() {
        assert_eq!(readable_value(&1e300_f64.to_string()), "1e300");
        assert_eq!(readable_value(&(-2.5e-9_f64).to_string()), "-2.5e-9");
        assert_eq!(readable_value("0.05"), "0.05");
        assert_eq!(readable_value("123456"), "123456");
        assert_eq!(readable_value("2147483647"), "2147483647");
        assert_eq!(readable_value("-2147483648"), "-2147483648");
        assert_eq!(
            readable_value("18446744073709551615"),
            "18446744073709551615"
        );
        assert_eq!(readable_value(&1e20_f64.to_string()), "1e20");
        assert_eq!(readable_value(&(-1e300_f64).to_string()), "-1e300");
        assert_eq!(readable_value("2147483647.5"), "2147483647.5");
        assert_eq!(readable_value("1000000000"), "1e9");
        assert_eq!(readable_value("4294967296"), "4294967296");
        assert_eq!(readable_value("9007199254740992"), "9007199254740992");
        assert_eq!(readable_value("1.5e300"), "1.5e300");
        assert_eq!(readable_value("\"abc\""), "\"abc\"");
        assert_eq!(readable_value("NaN"), "NaN");
    }
}
