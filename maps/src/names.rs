//! "Did you mean": the known name closest to a misspelt one, and serde's `unknown field` /
//! `unknown variant` messages rewritten to say it before their list of names.
//!
//! serde reports a misspelt key as ``unknown field `drive_rate_m_per_hr`, expected one of
//! `footprint_radius_m`, `drive_rate_m_per_h`, …`` — a list in declaration order, which a
//! message cut to a readable length can lose before the right name shows. [`unknown_name_message`]
//! puts the closest name first (`` (did you mean `drive_rate_m_per_h`?) ``) and keeps the list
//! whole: its names are the format's own, so only the misspelt name, which is the file's, is
//! cut.

/// A name as compared: lower case, `-` and spaces as `_` (`Drive-Rate` ~ `drive_rate`).
fn normalised(name: &str) -> Vec<char> {
    name.chars()
        .flat_map(char::to_lowercase)
        .map(|c| if matches!(c, '-' | ' ') { '_' } else { c })
        .collect()
}

/// Edits (insert, delete, substitute, swap two neighbours) that turn `a` into `b`: the optimal
/// string alignment distance.
fn distance(a: &[char], b: &[char]) -> usize {
    let (n, m) = (a.len(), b.len());
    // Rows i-2, i-1 and i of the edit table.
    let mut before: Vec<usize> = vec![0; m + 1];
    let mut prev: Vec<usize> = (0..=m).collect();
    let mut row: Vec<usize> = vec![0; m + 1];
    for i in 1..=n {
        row[0] = i;
        for j in 1..=m {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut d = (prev[j] + 1).min(row[j - 1] + 1).min(prev[j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d = d.min(before[j - 2] + 1);
            }
            row[j] = d;
        }
        std::mem::swap(&mut before, &mut prev);
        std::mem::swap(&mut prev, &mut row);
    }
    prev[m]
}

/// Longest name compared, characters: a longer one is no misspelling of a field name, and the
/// cost of comparing stays small whatever a file holds.
const MAX_COMPARED_CHARS: usize = 200;

/// The name of `candidates` that `word` most likely misspells, if one is close enough:
///
/// - the same name but for case, `-` or spaces (`Seed`, `drive-rate-m-per-h`);
/// - else the nearest by edit distance (an insertion, deletion, substitution or swap of two
///   neighbouring characters each), at most one edit per three characters of the longer name
///   and at least one (`nmae` → `name`, `drive_rate_m_per_hr` → `drive_rate_m_per_h`); the
///   first in `candidates`' order on a tie;
/// - else the one name that `word` begins, up to a `_` (a unit left off: `footprint_radius` →
///   `footprint_radius_m`), when only one does.
///
/// `None` when nothing is that close: a wrong suggestion misleads more than none.
#[must_use]
pub fn closest<'a>(word: &str, candidates: &[&'a str]) -> Option<&'a str> {
    let w = normalised(word);
    if w.is_empty() || w.len() > MAX_COMPARED_CHARS {
        return None;
    }
    let mut best: Option<(usize, &'a str)> = None;
    for &c in candidates {
        let n = normalised(c);
        if n.len() > MAX_COMPARED_CHARS || n == w && c == word {
            continue;
        }
        let d = distance(&w, &n);
        let allowed = (w.len().max(n.len()) / 3).max(1);
        if d <= allowed && best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, c));
        }
    }
    if let Some((_, c)) = best {
        return Some(c);
    }
    if w.len() < 3 {
        return None;
    }
    let mut prefixed = candidates.iter().filter(|c| {
        let n = normalised(c);
        n.len() > w.len() && n.starts_with(&w) && n[w.len()] == '_'
    });
    match (prefixed.next(), prefixed.next()) {
        (Some(c), None) => Some(c),
        _ => None,
    }
}

/// serde's report of a name it does not know, read back from its message.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownName<'a> {
    /// `field` or `variant`.
    pub kind: &'a str,
    /// The name the input holds.
    pub name: &'a str,
    /// The names expected, in the format's order (empty: "there are no fields").
    pub expected: Vec<&'a str>,
    /// What the message says after the list (serde_json's ` at line 3 column 7`).
    pub rest: &'a str,
}

/// Reads serde's `unknown field` / `unknown variant` message (``unknown field `x`, expected
/// one of `a`, `b` ``, `` expected `a` or `b` ``, `` expected `a` ``, `there are no fields`);
/// `None` for any other message.
#[must_use]
pub fn parse_unknown_name(message: &str) -> Option<UnknownName<'_>> {
    let (kind, after) = ["field", "variant"].iter().find_map(|kind| {
        message
            .strip_prefix("unknown ")?
            .strip_prefix(kind)?
            .strip_prefix(" `")
            .map(|after| (*kind, after))
    })?;
    if let Some(i) = after.find(&format!("`, there are no {kind}s")) {
        let rest = &after[i + format!("`, there are no {kind}s").len()..];
        return Some(UnknownName {
            kind,
            name: &after[..i],
            expected: Vec::new(),
            rest,
        });
    }
    let i = after
        .rfind("`, expected `")
        .or_else(|| after.rfind("`, expected one of `"))?;
    let name = &after[..i];
    let mut list = after[i + "`, expected ".len()..].trim_start_matches("one of ");
    let mut expected = Vec::new();
    while let Some(quoted) = list.strip_prefix('`') {
        let Some(end) = quoted.find('`') else {
            break;
        };
        expected.push(&quoted[..end]);
        list = &quoted[end + 1..];
        match [", ", " or "].iter().find_map(|sep| list.strip_prefix(sep)) {
            Some(next) if next.starts_with('`') => list = next,
            _ => break,
        }
    }
    if expected.is_empty() {
        return None;
    }
    Some(UnknownName {
        kind,
        name,
        expected,
        rest: list,
    })
}

impl UnknownName<'_> {
    /// The closest expected name to the one given ([`closest`]).
    #[must_use]
    pub fn suggestion(&self) -> Option<&str> {
        closest(self.name, &self.expected)
    }

    /// The message with the suggestion before the list: ``unknown field
    /// `drive_rate_m_per_hr` (did you mean `drive_rate_m_per_h`?), expected one of `…`,
    /// `…` ``. The given name is cut to `max_name_chars` and escaped
    /// ([`crate::input_file::excerpt`]); the expected names, the format's own, are listed
    /// whole.
    #[must_use]
    pub fn message(&self, max_name_chars: usize) -> String {
        let name = crate::input_file::excerpt(self.name, max_name_chars);
        let hint = self
            .suggestion()
            .map_or(String::new(), |s| format!(" (did you mean `{s}`?)"));
        let quoted: Vec<String> = self.expected.iter().map(|n| format!("`{n}`")).collect();
        let list = match quoted.as_slice() {
            [] => format!("there are no {}s", self.kind),
            [one] => format!("expected {one}"),
            [a, b] => format!("expected {a} or {b}"),
            many => format!("expected one of {}", many.join(", ")),
        };
        let rest = crate::input_file::excerpt(self.rest, max_name_chars);
        format!("unknown {} `{name}`{hint}, {list}{rest}", self.kind)
    }
}

/// serde's `unknown field` / `unknown variant` message with the closest name first and the list
/// whole ([`UnknownName::message`]); `None` for any other message.
#[must_use]
pub fn unknown_name_message(message: &str, max_name_chars: usize) -> Option<String> {
    parse_unknown_name(message).map(|u| u.message(max_name_chars))
}

#[cfg(test)]
mod tests {
    use super::*;

    const ROVER: [&str; 5] = [
        "footprint_radius_m",
        "drive_rate_m_per_h",
        "step_m",
        "waypoint_tolerance_m",
        "max_drive_m",
    ];

    #[test]
    fn close_misspellings_find_their_name() {
        for (typo, right) in [
            ("drive_rate_m_per_hr", "drive_rate_m_per_h"),
            ("drive-rate-m-per-h", "drive_rate_m_per_h"),
            ("Step_M", "step_m"),
            ("stepm", "step_m"),
            ("footprint_radius", "footprint_radius_m"),
            ("footprnit_radius_m", "footprint_radius_m"),
            ("waypoint_tolerence_m", "waypoint_tolerance_m"),
        ] {
            assert_eq!(closest(typo, &ROVER), Some(right), "{typo}");
        }
        assert_eq!(closest("nmae", &["name", "seed"]), Some("name"));
        assert_eq!(closest("seeed", &["name", "seed"]), Some("seed"));
    }

    #[test]
    fn far_or_ambiguous_names_get_no_suggestion() {
        for typo in ["colour", "x", "", "speed", "battery_capacity_wh"] {
            assert_eq!(closest(typo, &ROVER), None, "{typo}");
        }
        // `drive` begins two names: no guess between them.
        assert_eq!(
            closest("drive", &["drive_start_lmst", "drive_end_lmst"]),
            None
        );
        assert_eq!(closest(&"a".repeat(100_000), &ROVER), None);
    }

    #[test]
    fn distance_counts_swaps_as_one_edit() {
        let d = |a: &str, b: &str| distance(&normalised(a), &normalised(b));
        assert_eq!(d("name", "nmae"), 1);
        assert_eq!(d("kitten", "sitting"), 3);
        assert_eq!(d("", "abc"), 3);
        assert_eq!(d("abc", "abc"), 0);
    }

    #[test]
    fn serde_messages_are_read_back() {
        let u = parse_unknown_name(
            "unknown field `drive_rate_m_per_hr`, expected one of `footprint_radius_m`, `drive_rate_m_per_h`, `step_m`",
        )
        .expect("parsed");
        assert_eq!(u.kind, "field");
        assert_eq!(u.name, "drive_rate_m_per_hr");
        assert_eq!(
            u.expected,
            ["footprint_radius_m", "drive_rate_m_per_h", "step_m"]
        );
        assert_eq!(
            u.message(120),
            "unknown field `drive_rate_m_per_hr` (did you mean `drive_rate_m_per_h`?), expected \
             one of `footprint_radius_m`, `drive_rate_m_per_h`, `step_m`"
        );
        let two = parse_unknown_name(
            "unknown variant `censsus`, expected `census` or `ncc` at line 1 column 9",
        )
        .expect("parsed");
        assert_eq!(two.expected, ["census", "ncc"]);
        assert_eq!(two.rest, " at line 1 column 9");
        assert_eq!(
            two.message(120),
            "unknown variant `censsus` (did you mean `census`?), expected `census` or `ncc` at line 1 column 9"
        );
        let one = parse_unknown_name("unknown field `sede`, expected `seed`").expect("parsed");
        assert_eq!(one.suggestion(), Some("seed"));
        let none = parse_unknown_name("unknown field `x`, there are no fields").expect("parsed");
        assert_eq!(none.message(120), "unknown field `x`, there are no fields");
        assert_eq!(parse_unknown_name("missing field `name`"), None);
        assert_eq!(
            parse_unknown_name("invalid type: string \"x\", expected f64"),
            None
        );
    }

    #[test]
    fn the_given_name_is_cut_and_escaped_the_list_is_not() {
        let long = format!("unknown field `{}\u{1b}`, expected `seed`", "y".repeat(300));
        let m = unknown_name_message(&long, 20).expect("parsed");
        assert!(m.contains('…') && !m.contains('\u{1b}'), "{m}");
        assert!(m.ends_with("expected `seed`"), "{m}");
    }
}
