//! Text-aware mutations: numbers replaced by extremes (or by plausible values that stress what
//! comes after validation), hostile strings, dropped / duplicated / moved lines, TOML tables,
//! bracketed spans, deep nesting, identifiers.

use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use super::{Format, Mutator, below, pick, repeat_count};

/// Numbers at the edges: ±1e300, NaN, infinities, zeros, subnormals, integer limits, huge
/// exponents and digit strings.
const EXTREME_NUMBERS: &[&str] = &[
    "1e300",
    "-1e300",
    "nan",
    "-nan",
    "NaN",
    "inf",
    "-inf",
    "+inf",
    "Infinity",
    "-Infinity",
    "0",
    "-0",
    "0.0",
    "-0.0",
    "1e-300",
    "5e-324",
    "1e308",
    "1.7976931348623157e308",
    "1e309",
    "1e99999",
    "-1e99999",
    "1e-99999",
    "18446744073709551615",
    "18446744073709551616",
    "9223372036854775807",
    "-9223372036854775808",
    "-9223372036854775809",
    "4294967295",
    "4294967296",
    "2147483648",
    "65535",
    "65536",
    "-1",
    "1",
    "2",
    "3",
    "1e20",
    "1e9",
    "-1e9",
    "100000",
    "20000",
    "20001",
    "0.5",
    "1e-9",
    "0x7fffffff",
    "0o777",
    "0b101",
    "1_000_000",
    "1__0",
    "00001",
    "1.",
    ".5",
    "1e",
    "--1",
    "123456789012345678901234567890123456789012345678901234567890",
    "0.000000000000000000000000000000000000000000000000000000000001",
];

/// Numbers a validator may let through but that stress what comes after it (fine grids,
/// coordinates at or past a map's edge, long drives).
const PLAUSIBLE_NUMBERS: &[&str] = &[
    "0.01",
    "0.02",
    "0.05",
    "0.1",
    "0.25",
    "0.5",
    "1",
    "2",
    "10",
    "49.9",
    "50",
    "99",
    "600",
    "1199.9",
    "1200",
    "1200.0001",
    "2000",
    "5000",
    "9600",
    "-0.001",
    "-1",
    "1e6",
    "1e-4",
];

/// Hostile string contents: empty, control characters, bidi overrides, long runs, paths to
/// special files, format specifiers, quotes and escapes, and the enum words of the formats.
const HOSTILE_STRINGS: &[&str] = &[
    "",
    " ",
    "\u{0}",
    "\\u0000",
    "\t\r",
    "\u{7}\u{1b}[31m",
    "\u{202e}evil",
    "\u{feff}",
    "💥",
    "a\nb",
    "\\",
    "\\\"",
    "\\x41",
    "\\uD800",
    "\\U0010FFFF",
    "\\U00110000",
    "../../../../../../etc/passwd",
    "/dev/zero",
    "/dev/urandom",
    "/dev/null",
    "/proc/self/mem",
    "/",
    ".",
    "..",
    "%s%n%x",
    "${HOME}",
    "CON",
    "keep_out",
    "keep_in",
    "census",
    "ncc",
    "mi",
    "statistical",
    "onboard",
    "ground",
    "extension",
    "NO_PATH",
    "KEEP_OUT",
    "00:00",
    "23:59",
    "24:00",
    "11:60",
    "-1:00",
    "99999999:00",
    "1:5",
    "12:30:45",
    "12",
    ":",
    "FeatureCollection",
    "Feature",
    "Polygon",
    "MultiPolygon",
    "Point",
    "LineString",
    "GeometryCollection",
];

impl Mutator<'_> {
    pub(super) fn gentle_op(&self, rng: &mut ChaCha8Rng, d: &mut Vec<u8>) -> &'static str {
        match below(rng, 10) {
            0..=5 => {
                let spans = number_spans(d);
                if spans.is_empty() {
                    return "numbers-none";
                }
                let (a, b) = *pick(rng, &spans);
                let numbers = if rng.random_bool(0.5) {
                    EXTREME_NUMBERS
                } else {
                    PLAUSIBLE_NUMBERS
                };
                d.splice(a..b, pick(rng, numbers).bytes());
                "extreme-number"
            }
            6 | 7 => {
                let spans = string_spans(d);
                if spans.is_empty() {
                    return "strings-none";
                }
                let (a, b) = *pick(rng, &spans);
                let repl = if self.dict.is_empty() || rng.random_bool(0.5) {
                    pick(rng, HOSTILE_STRINGS).as_bytes().to_vec()
                } else {
                    // A dictionary token without its quotes (paths, keywords).
                    let t = pick(rng, self.dict);
                    t.strip_prefix(b"\"")
                        .and_then(|t| t.strip_suffix(b"\""))
                        .unwrap_or(t)
                        .to_vec()
                };
                d.splice(a..b, repl);
                "hostile-string"
            }
            8 => {
                let lines = line_spans(d);
                if lines.is_empty() {
                    return "lines-none";
                }
                let (a, b) = *pick(rng, &lines);
                d.drain(a..b);
                "drop-line"
            }
            _ => {
                let lines = line_spans(d);
                if lines.is_empty() {
                    return "lines-none";
                }
                let (a, b) = *pick(rng, &lines);
                let line = d[a..b].to_vec();
                let at = line_start(d, below(rng, d.len() + 1));
                d.splice(at..at, line);
                "copy-line"
            }
        }
    }

    pub(super) fn text_op(&self, rng: &mut ChaCha8Rng, d: &mut Vec<u8>) -> &'static str {
        match below(rng, 10) {
            0 | 1 => {
                let spans = number_spans(d);
                if spans.is_empty() {
                    return "numbers-none";
                }
                let (a, b) = *pick(rng, &spans);
                let repl = pick(rng, EXTREME_NUMBERS).as_bytes().to_vec();
                d.splice(a..b, repl);
                "extreme-number"
            }
            2 => {
                let spans = string_spans(d);
                if spans.is_empty() {
                    return "strings-none";
                }
                let (a, b) = *pick(rng, &spans);
                let repl: Vec<u8> = match below(rng, 4) {
                    0 => {
                        let c = *pick(rng, &["a", "é", "\\u0007", "\u{0}", "9"]);
                        c.repeat(*pick(rng, &[200, 5_000, 100_000])).into_bytes()
                    }
                    _ => pick(rng, HOSTILE_STRINGS).as_bytes().to_vec(),
                };
                d.splice(a..b, repl);
                "hostile-string"
            }
            3 => {
                let lines = line_spans(d);
                if lines.is_empty() {
                    return "lines-none";
                }
                let (a, b) = *pick(rng, &lines);
                match below(rng, 3) {
                    0 => {
                        d.drain(a..b);
                        "drop-line"
                    }
                    1 => {
                        let line = d[a..b].to_vec();
                        let reps = repeat_count(rng).min(self.max_len / line.len().max(1));
                        d.splice(b..b, line.iter().copied().cycle().take(line.len() * reps));
                        "duplicate-line"
                    }
                    _ => {
                        let line = d[a..b].to_vec();
                        d.drain(a..b);
                        let at = line_start(d, below(rng, d.len() + 1));
                        d.splice(at..at, line);
                        "move-line"
                    }
                }
            }
            4 if self.format == Format::Toml => {
                let tables = toml_table_spans(d);
                if tables.is_empty() {
                    return "tables-none";
                }
                let (a, b) = *pick(rng, &tables);
                match below(rng, 3) {
                    0 => {
                        d.drain(a..b);
                        "drop-table"
                    }
                    1 => {
                        let table = d[a..b].to_vec();
                        let reps = repeat_count(rng).min(self.max_len / table.len().max(1));
                        d.splice(b..b, table.iter().copied().cycle().take(table.len() * reps));
                        "duplicate-table"
                    }
                    _ => {
                        // `[x]` ↔ `[[x]]`: a table where an array of tables is expected.
                        let header_end = d[a..b]
                            .iter()
                            .position(|&c| c == b'\n')
                            .map_or(b, |p| a + p);
                        let header = String::from_utf8_lossy(&d[a..header_end]).into_owned();
                        let name = header.trim().trim_matches(|c| c == '[' || c == ']');
                        let new = if header.trim_start().starts_with("[[") {
                            format!("[{name}]")
                        } else {
                            format!("[[{name}]]")
                        };
                        d.splice(a..header_end, new.into_bytes());
                        "retype-table"
                    }
                }
            }
            5 | 6 => {
                let Some((a, b)) = bracket_span(rng, d) else {
                    return "brackets-none";
                };
                match below(rng, 5) {
                    0 => {
                        d.drain(a..b);
                        "drop-span"
                    }
                    1 => {
                        let span = d[a..b].to_vec();
                        let reps = repeat_count(rng).min(self.max_len / (span.len() + 2));
                        let mut extra = Vec::with_capacity((span.len() + 2) * reps);
                        for _ in 0..reps {
                            extra.extend_from_slice(b", ");
                            extra.extend_from_slice(&span);
                        }
                        d.splice(b..b, extra);
                        "duplicate-span"
                    }
                    2 => {
                        let k = *pick(rng, &[1, 2, 16, 130]);
                        let (open, close) = (d[a], d[b - 1]);
                        let mut wrapped = vec![open; k];
                        if open == b'{' {
                            wrapped.clear();
                            for _ in 0..k {
                                wrapped.extend_from_slice(if self.format == Format::Json {
                                    b"{\"a\": "
                                } else {
                                    b"{ a = "
                                });
                            }
                        }
                        wrapped.extend_from_slice(&d[a..b]);
                        wrapped.extend(std::iter::repeat_n(close, k));
                        d.splice(a..b, wrapped);
                        "wrap-span"
                    }
                    3 => {
                        let repl = *pick(
                            rng,
                            &[
                                "[]", "{}", "null", "0", "\"\"", "true", "[[]]", "[0]", "[0, 0]",
                                "[[0, 0]]",
                            ],
                        );
                        d.splice(a..b, repl.bytes());
                        "replace-span"
                    }
                    _ => {
                        let Some((c, e)) = bracket_span(rng, d) else {
                            return "brackets-none";
                        };
                        let other = d[c..e].to_vec();
                        d.splice(a..b, other);
                        "swap-span"
                    }
                }
            }
            7 => {
                let depth = *pick(rng, &[64, 127, 129, 300, 3_000, 50_000]);
                let depth = depth.min(self.max_len / 8);
                let (open, leaf, close): (&[u8], &[u8], &[u8]) =
                    match (self.format, rng.random_bool(0.5)) {
                        (Format::Json, true) => (b"{\"a\":", b"1", b"}"),
                        (Format::Toml, true) => (b"{a=", b"1", b"}"),
                        _ => (b"[", b"0", b"]"),
                    };
                let mut nest = Vec::with_capacity(depth * (open.len() + close.len()) + 1);
                for _ in 0..depth {
                    nest.extend_from_slice(open);
                }
                nest.extend_from_slice(leaf);
                for _ in 0..depth {
                    nest.extend_from_slice(close);
                }
                // After a `=` or `:` when there is one, so the nesting lands on a value.
                let sep = if self.format == Format::Json {
                    b':'
                } else {
                    b'='
                };
                let seps: Vec<usize> = d
                    .iter()
                    .enumerate()
                    .filter(|(_, c)| **c == sep)
                    .map(|(i, _)| i + 1)
                    .collect();
                if seps.is_empty() {
                    let at = below(rng, d.len() + 1);
                    d.splice(at..at, nest);
                } else {
                    let at = *pick(rng, &seps);
                    let end = value_end(d, at);
                    d.splice(at..end, nest);
                }
                "deep-nesting"
            }
            _ => {
                let words = word_spans(d);
                if words.is_empty() {
                    return "words-none";
                }
                let (a, b) = *pick(rng, &words);
                let repl = if !self.dict.is_empty() && rng.random_bool(0.5) {
                    pick(rng, self.dict).clone()
                } else {
                    let (c, e) = *pick(rng, &words);
                    d[c..e].to_vec()
                };
                d.splice(a..b, repl);
                "replace-word"
            }
        }
    }
}

fn is_word(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// The start of the line holding byte `i`.
pub(super) fn line_start(d: &[u8], i: usize) -> usize {
    d[..i.min(d.len())]
        .iter()
        .rposition(|&c| c == b'\n')
        .map_or(0, |p| p + 1)
}

/// Spans of number-like tokens: a digit (or sign then digit) not inside a word, then word
/// characters, dots and signs.
fn number_spans(d: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < d.len() {
        let starts = (d[i].is_ascii_digit()
            || (matches!(d[i], b'-' | b'+') && d.get(i + 1).is_some_and(u8::is_ascii_digit)))
            && (i == 0 || !is_word(d[i - 1]));
        if starts {
            let mut j = i + 1;
            while j < d.len() && (is_word(d[j]) || matches!(d[j], b'.' | b'-' | b'+')) {
                j += 1;
            }
            spans.push((i, j));
            i = j;
        } else {
            i += 1;
        }
    }
    spans
}

/// Contents of double-quoted strings (naively paired, within a line).
fn string_spans(d: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut open = None;
    for (i, &c) in d.iter().enumerate() {
        match (c, open) {
            (b'\n', _) => open = None,
            (b'"', None) => open = Some(i + 1),
            (b'"', Some(a)) if i > 0 && d[i - 1] != b'\\' => {
                spans.push((a, i));
                open = None;
            }
            _ => {}
        }
    }
    spans
}

/// Lines, each with its newline.
fn line_spans(d: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut a = 0;
    for (i, &c) in d.iter().enumerate() {
        if c == b'\n' {
            spans.push((a, i + 1));
            a = i + 1;
        }
    }
    if a < d.len() {
        spans.push((a, d.len()));
    }
    spans
}

/// TOML tables: from a line starting with `[` to the next such line.
fn toml_table_spans(d: &[u8]) -> Vec<(usize, usize)> {
    let starts: Vec<usize> = line_spans(d)
        .into_iter()
        .filter(|&(a, _)| d[a..].iter().find(|c| !c.is_ascii_whitespace()) == Some(&b'['))
        .map(|(a, _)| a)
        .collect();
    starts
        .iter()
        .enumerate()
        .map(|(k, &a)| (a, starts.get(k + 1).copied().unwrap_or(d.len())))
        .collect()
}

/// Identifiers.
fn word_spans(d: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < d.len() {
        if d[i].is_ascii_alphabetic() || d[i] == b'_' {
            let mut j = i + 1;
            while j < d.len() && is_word(d[j]) {
                j += 1;
            }
            spans.push((i, j));
            i = j;
        } else {
            i += 1;
        }
    }
    spans
}

/// A random `[...]` or `{...}` span with its brackets (matched by depth, ignoring strings).
fn bracket_span(rng: &mut ChaCha8Rng, d: &[u8]) -> Option<(usize, usize)> {
    let opens: Vec<usize> = d
        .iter()
        .enumerate()
        .filter(|(_, c)| matches!(c, b'[' | b'{'))
        .map(|(i, _)| i)
        .collect();
    if opens.is_empty() {
        return None;
    }
    let a = *pick(rng, &opens);
    let (open, close) = if d[a] == b'[' {
        (b'[', b']')
    } else {
        (b'{', b'}')
    };
    let mut depth = 0usize;
    for (i, &c) in d.iter().enumerate().skip(a) {
        if c == open {
            depth += 1;
        } else if c == close {
            depth -= 1;
            if depth == 0 {
                return Some((a, i + 1));
            }
        }
    }
    None
}

/// End of the value starting at `at`: the end of its line, or of its bracketed span.
fn value_end(d: &[u8], at: usize) -> usize {
    let mut depth = 0i64;
    for (i, &c) in d.iter().enumerate().skip(at) {
        match c {
            b'[' | b'{' => depth += 1,
            b']' | b'}' if depth == 0 => return i,
            b']' | b'}' => depth -= 1,
            b',' | b'\n' if depth == 0 => return i,
            _ => {}
        }
    }
    d.len()
}
