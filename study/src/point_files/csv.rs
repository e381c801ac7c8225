//! The CSV dialect of solsim's point files: commas separate fields, a field may be
//! double-quoted (`""` for a quote inside), unquoted fields are trimmed, blank lines are
//! skipped, a UTF-8 byte-order mark is dropped; the first line is a header row naming the
//! columns.

use super::error::PointFileError;

/// A CSV text's header row.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CsvHeader {
    /// Its 1-based line number.
    pub line: usize,
    /// Its fields: the column names.
    pub fields: Vec<String>,
}

/// The data rows of a CSV text below its header, each split into fields, with its 1-based
/// line number.
pub struct CsvRows<'a> {
    file: String,
    lines: Box<dyn Iterator<Item = (usize, &'a str)> + 'a>,
    /// The number of fields every row must have, and how the error says so.
    width: Option<(usize, String)>,
}

impl CsvRows<'_> {
    /// Rows that must each have `fields` fields (the header's); `expected` is what the error
    /// of a row with another number says (`2 fields (x_m,y_m)`).
    #[must_use]
    pub fn of_width(mut self, fields: usize, expected: String) -> Self {
        self.width = Some((fields, expected));
        self
    }
}

impl Iterator for CsvRows<'_> {
    type Item = Result<(usize, Vec<String>), PointFileError>;

    fn next(&mut self) -> Option<Self::Item> {
        let (line, text) = self.lines.next()?;
        let fields = match split_fields(text) {
            Ok(fields) => fields,
            Err(error) => {
                return Some(Err(PointFileError::CsvSyntax {
                    file: self.file.clone(),
                    line,
                    error,
                }));
            }
        };
        match &self.width {
            Some((n, expected)) if fields.len() != *n => Some(Err(PointFileError::field(
                &self.file,
                format!("line {line}"),
                expected.clone(),
                fields.len(),
            ))),
            _ => Some(Ok((line, fields))),
        }
    }
}

/// Reads CSV `text` of file `file` (as displayed): its header row, and its data rows.
///
/// # Errors
/// [`PointFileError::Empty`] (saying `expected_header`) for a text of blank lines only;
/// [`PointFileError::CsvSyntax`] for a header row that does not split into fields.
pub fn read_csv<'a>(
    text: &'a str,
    file: &str,
    expected_header: &'static str,
) -> Result<(CsvHeader, CsvRows<'a>), PointFileError> {
    let mut lines = numbered_lines(text);
    let Some((line, header)) = lines.next() else {
        return Err(PointFileError::Empty {
            file: file.to_owned(),
            expected: expected_header,
        });
    };
    let fields = split_fields(header).map_err(|error| PointFileError::CsvSyntax {
        file: file.to_owned(),
        line,
        error,
    })?;
    let rows = CsvRows {
        file: file.to_owned(),
        lines: Box::new(lines),
        width: None,
    };
    Ok((CsvHeader { line, fields }, rows))
}

/// A CSV file's non-blank lines with their 1-based line numbers, after a UTF-8 byte-order mark.
fn numbered_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.strip_prefix('\u{feff}')
        .unwrap_or(text)
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l))
        .filter(|(_, l)| !l.trim().is_empty())
}

/// Split one CSV line into fields: commas separate; a field may be double-quoted (with `""` for a
/// quote inside); unquoted fields are trimmed.
///
/// # Errors
/// `unterminated quoted field`, or `unexpected text after a quoted field`.
fn split_fields(line: &str) -> Result<Vec<String>, &'static str> {
    let mut fields = Vec::new();
    let mut chars = line.chars().peekable();
    loop {
        while chars.next_if(|c| *c == ' ' || *c == '\t').is_some() {}
        let mut field = String::new();
        if chars.next_if_eq(&'"').is_some() {
            loop {
                match chars.next() {
                    Some('"') if chars.next_if_eq(&'"').is_some() => field.push('"'),
                    Some('"') => break,
                    Some(c) => field.push(c),
                    None => return Err("unterminated quoted field"),
                }
            }
            while chars.next_if(|c| *c == ' ' || *c == '\t').is_some() {}
            match chars.next() {
                None => {
                    fields.push(field);
                    return Ok(fields);
                }
                Some(',') => fields.push(field),
                Some(_) => return Err("unexpected text after a quoted field"),
            }
        } else {
            loop {
                match chars.next() {
                    None => {
                        fields.push(field.trim().to_owned());
                        return Ok(fields);
                    }
                    Some(',') => break,
                    Some(c) => field.push(c),
                }
            }
            fields.push(field.trim().to_owned());
        }
    }
}
