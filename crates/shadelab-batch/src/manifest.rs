//! Manifests: which meshes to render, one per line, read as a stream.
//!
//! Two formats, chosen by the file's extension: CSV (`.csv`) with a header
//! line naming the columns (`path` required; `id`, `views`, `size`, `shading`
//! optional), and JSON Lines (anything else) with one object per line
//! (`{"path": "...", "id": "...", "views": 6, "size": "256x256", "shading":
//! "all"}`, every key but `path` optional, unknown keys refused). Blank lines
//! are skipped in both. A CSV field may be quoted, but a quoted field may not
//! span lines: every record is one line, so that line numbers are exact and
//! one bad line never hides the next.
//!
//! The manifest is never held whole: [`Manifest`] yields one [`Entry`] at a
//! time, and no line is read past [`MAX_LINE_BYTES`], so memory stays bounded
//! however large (or hostile) the file is. A line that cannot be parsed is a
//! [`LineError`] carrying its line number; the run records it and goes on.

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::plan::{parse_modes, parse_size, Views};
use crate::BatchError;
use shadelab_core::Shading;

/// The longest manifest line read, in bytes (a line past it is an error).
pub const MAX_LINE_BYTES: usize = 64 * 1024;

/// One mesh of the manifest, as its line gives it.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// 1-based line number in the manifest.
    pub line: u64,
    /// The mesh file as written (relative to the manifest's folder).
    pub path: String,
    /// The id as written, if the line gives one.
    pub id: Option<String>,
    /// Views for this mesh instead of the run's.
    pub views: Option<Views>,
    /// Image size for this mesh instead of the run's.
    pub size: Option<(u32, u32)>,
    /// Modes for this mesh instead of the run's.
    pub modes: Option<Vec<Shading>>,
}

/// A manifest line that could not be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}:{line}: {message}")]
pub struct LineError {
    /// The manifest, as named to the run.
    pub file: String,
    /// 1-based line number.
    pub line: u64,
    /// What is wrong.
    pub message: String,
}

/// The manifest's format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ManifestFormat {
    /// One JSON object per line.
    JsonLines,
    /// A header line, then comma-separated values.
    Csv,
}

impl ManifestFormat {
    /// The format a file's extension names: `.csv` is CSV, anything else JSON Lines.
    pub fn of(path: &Path) -> ManifestFormat {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("csv") => ManifestFormat::Csv,
            _ => ManifestFormat::JsonLines,
        }
    }
}

/// A manifest being read, one entry at a time.
pub struct Manifest {
    name: String,
    dir: PathBuf,
    format: ManifestFormat,
    reader: Box<dyn BufRead + Send>,
    line: u64,
    columns: Vec<Column>,
    buf: Vec<u8>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Column {
    Path,
    Id,
    Views,
    Size,
    Shading,
}

impl Column {
    const ALL: [(&'static str, Column); 5] = [
        ("path", Column::Path),
        ("id", Column::Id),
        ("views", Column::Views),
        ("size", Column::Size),
        ("shading", Column::Shading),
    ];
}

impl Manifest {
    /// Opens a manifest file; it must be a regular file (a FIFO would block).
    ///
    /// # Errors
    /// [`BatchError::Manifest`] when the file cannot be opened, is not a
    /// regular file, or (CSV) its header is unusable.
    pub fn open(path: &Path) -> Result<Manifest, BatchError> {
        let name = path.display().to_string();
        let fail = |message: String| BatchError::Manifest {
            path: name.clone(),
            message,
        };
        let meta = std::fs::metadata(path).map_err(|e| fail(e.to_string()))?;
        if !meta.is_file() {
            return Err(fail("not a regular file".into()));
        }
        let file = std::fs::File::open(path).map_err(|e| fail(e.to_string()))?;
        let dir = path
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."))
            .to_path_buf();
        Manifest::from_reader(
            Box::new(BufReader::with_capacity(64 * 1024, file)),
            &name,
            dir,
            ManifestFormat::of(path),
        )
    }

    /// A manifest read from `reader`; `name` is used in messages and `dir`
    /// is the folder relative paths are taken from.
    ///
    /// # Errors
    /// As [`Manifest::open`].
    pub fn from_reader(
        reader: Box<dyn BufRead + Send>,
        name: &str,
        dir: PathBuf,
        format: ManifestFormat,
    ) -> Result<Manifest, BatchError> {
        let mut manifest = Manifest {
            name: name.to_owned(),
            dir,
            format,
            reader,
            line: 0,
            columns: Vec::new(),
            buf: Vec::new(),
        };
        if format == ManifestFormat::Csv {
            manifest.read_header()?;
        }
        Ok(manifest)
    }

    /// The folder the manifest's relative paths are taken from.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The manifest's name in messages.
    pub fn name(&self) -> &str {
        &self.name
    }

    fn read_header(&mut self) -> Result<(), BatchError> {
        let name = self.name.clone();
        let fail = |line: u64, message: String| BatchError::Manifest {
            path: format!("{name}:{line}"),
            message,
        };
        let header = loop {
            match self.next_line() {
                None => return Err(fail(self.line.max(1), "no header line".into())),
                Some(Err(e)) => return Err(fail(e.line, e.message)),
                Some(Ok(text)) if text.trim().is_empty() => continue,
                Some(Ok(text)) => break text,
            }
        };
        let fields = csv_fields(&header).map_err(|m| fail(self.line, m))?;
        let mut columns = Vec::new();
        for field in fields {
            let name = field.trim();
            let Some(&(_, column)) = Column::ALL.iter().find(|(n, _)| *n == name) else {
                return Err(fail(
                    self.line,
                    format!(
                        "unknown column {name:?}; the columns are path (required), id, views, size, shading"
                    ),
                ));
            };
            if columns.contains(&column) {
                return Err(fail(self.line, format!("column {name:?} appears twice")));
            }
            columns.push(column);
        }
        if !columns.contains(&Column::Path) {
            return Err(fail(self.line, "the header has no \"path\" column".into()));
        }
        self.columns = columns;
        Ok(())
    }

    /// The next line's text (without its line break), bounded by
    /// [`MAX_LINE_BYTES`]; `None` at the end.
    fn next_line(&mut self) -> Option<Result<String, LineError>> {
        self.buf.clear();
        self.line += 1;
        let limit = MAX_LINE_BYTES as u64 + 1;
        let read = (&mut self.reader)
            .take(limit)
            .read_until(b'\n', &mut self.buf);
        match read {
            Err(e) => return Some(Err(self.error(format!("cannot read: {e}")))),
            Ok(0) => return None,
            Ok(_) => {}
        }
        if self.buf.last() != Some(&b'\n') && self.buf.len() as u64 == limit {
            // Skip the rest of the over-long line, a bounded chunk at a time.
            loop {
                self.buf.clear();
                match (&mut self.reader)
                    .take(limit)
                    .read_until(b'\n', &mut self.buf)
                {
                    Ok(0) | Err(_) => break,
                    Ok(_) if self.buf.last() == Some(&b'\n') => break,
                    Ok(_) => {}
                }
            }
            return Some(Err(
                self.error(format!("the line is longer than {MAX_LINE_BYTES} bytes"))
            ));
        }
        while matches!(self.buf.last(), Some(b'\n' | b'\r')) {
            self.buf.pop();
        }
        match std::str::from_utf8(&self.buf) {
            Ok(text) => Some(Ok(text.to_owned())),
            Err(_) => Some(Err(self.error("the line is not UTF-8 text".into()))),
        }
    }

    fn error(&self, message: String) -> LineError {
        LineError {
            file: self.name.clone(),
            line: self.line,
            message,
        }
    }

    fn parse(&self, text: &str) -> Result<Entry, String> {
        match self.format {
            ManifestFormat::JsonLines => parse_json_line(text, self.line),
            ManifestFormat::Csv => self.parse_csv_line(text),
        }
    }

    fn parse_csv_line(&self, text: &str) -> Result<Entry, String> {
        let fields = csv_fields(text)?;
        if fields.len() != self.columns.len() {
            return Err(format!(
                "{} fields, but the header names {} columns",
                fields.len(),
                self.columns.len()
            ));
        }
        let mut entry = Entry {
            line: self.line,
            path: String::new(),
            id: None,
            views: None,
            size: None,
            modes: None,
        };
        for (column, field) in self.columns.iter().zip(fields) {
            // An empty optional field means "the run's value".
            if field.is_empty() && *column != Column::Path {
                continue;
            }
            match column {
                Column::Path => entry.path = field,
                Column::Id => entry.id = Some(field),
                Column::Views => entry.views = Some(field.parse().map_err(key("views"))?),
                Column::Size => entry.size = Some(parse_size(&field).map_err(key("size"))?),
                Column::Shading => entry.modes = Some(parse_modes(&field).map_err(key("shading"))?),
            }
        }
        if entry.path.is_empty() {
            return Err("path is empty".into());
        }
        Ok(entry)
    }
}

fn key(name: &'static str) -> impl Fn(String) -> String {
    move |m| format!("{name}: {m}")
}

impl Iterator for Manifest {
    type Item = Result<Entry, LineError>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            let text = match self.next_line()? {
                Ok(text) => text,
                Err(e) => return Some(Err(e)),
            };
            if text.trim().is_empty() {
                continue;
            }
            return Some(self.parse(&text).map_err(|m| self.error(m)));
        }
    }
}

/// One CSV record on one line.
fn csv_fields(text: &str) -> Result<Vec<String>, String> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .from_reader(text.as_bytes());
    let mut record = csv::StringRecord::new();
    match reader.read_record(&mut record) {
        Ok(true) => {}
        Ok(false) => return Ok(Vec::new()),
        Err(e) => return Err(format!("not a CSV record: {e}")),
    }
    if reader
        .read_record(&mut csv::StringRecord::new())
        .unwrap_or(true)
    {
        return Err("a quoted field must not span lines".into());
    }
    Ok(record.iter().map(str::to_owned).collect())
}

/// A number or a string, as JSON may give `views`.
#[derive(Deserialize)]
#[serde(untagged)]
enum NumberOrText {
    Number(u64),
    Text(String),
}

/// One or several names, as JSON may give `shading`.
#[derive(Deserialize)]
#[serde(untagged)]
enum OneOrMany {
    One(String),
    Many(Vec<String>),
}

/// `"WxH"` or `[W, H]`, as JSON may give `size`.
#[derive(Deserialize)]
#[serde(untagged)]
enum SizeValue {
    Text(String),
    Pair([u32; 2]),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct JsonEntry {
    path: String,
    id: Option<String>,
    views: Option<NumberOrText>,
    size: Option<SizeValue>,
    shading: Option<OneOrMany>,
}

fn parse_json_line(text: &str, line: u64) -> Result<Entry, String> {
    let raw: JsonEntry = serde_json::from_str(text).map_err(|e| {
        // serde_json counts lines within the text, which is always 1 here.
        let message = e.to_string();
        match message.rsplit_once(" at line ") {
            Some((what, _)) => format!("{what} (column {})", e.column()),
            None => message,
        }
    })?;
    if raw.path.is_empty() {
        return Err("path is empty".into());
    }
    let views = match raw.views {
        None => None,
        Some(NumberOrText::Number(n)) => Some(
            u32::try_from(n)
                .map_err(|_| format!("views: {n} is too many"))
                .and_then(|n| Views::ring(n).map_err(key("views")))?,
        ),
        Some(NumberOrText::Text(t)) => Some(t.parse().map_err(key("views"))?),
    };
    let size = match raw.size {
        None => None,
        Some(SizeValue::Text(t)) => Some(parse_size(&t).map_err(key("size"))?),
        Some(SizeValue::Pair([w, h])) => {
            Some(parse_size(&format!("{w}x{h}")).map_err(key("size"))?)
        }
    };
    let modes = match raw.shading {
        None => None,
        Some(OneOrMany::One(t)) => Some(parse_modes(&t).map_err(key("shading"))?),
        Some(OneOrMany::Many(list)) => Some(parse_modes(&list.join(",")).map_err(key("shading"))?),
    };
    Ok(Entry {
        line,
        path: raw.path,
        id: raw.id,
        views,
        size,
        modes,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str, format: ManifestFormat) -> Vec<Result<Entry, LineError>> {
        let reader = Box::new(std::io::Cursor::new(text.as_bytes().to_vec()));
        Manifest::from_reader(reader, "m", PathBuf::from("."), format)
            .unwrap()
            .collect()
    }

    #[test]
    fn json_lines_with_overrides_and_blank_lines() {
        let got = read(
            "{\"path\": \"a.obj\"}\n\n{\"path\": \"b.stl\", \"id\": \"b\", \"views\": \"cube\", \"size\": [64, 32], \"shading\": [\"flat\", \"phong\"]}\r\n",
            ManifestFormat::JsonLines,
        );
        assert_eq!(got.len(), 2);
        let a = got[0].as_ref().unwrap();
        assert_eq!(
            (a.line, a.path.as_str(), a.id.as_deref()),
            (1, "a.obj", None)
        );
        let b = got[1].as_ref().unwrap();
        assert_eq!(b.line, 3);
        assert_eq!(b.views, Some(Views::Cube));
        assert_eq!(b.size, Some((64, 32)));
        assert_eq!(b.modes, Some(vec![Shading::Flat, Shading::Phong]));
    }

    #[test]
    fn a_bad_json_line_is_an_error_that_names_its_line_and_the_next_line_still_reads() {
        let got = read(
            "{\"path\": \"a.obj\", \"colour\": 1}\nnot json\n{\"path\": \"c.obj\", \"views\": 0}\n{\"path\": \"d.obj\"}\n",
            ManifestFormat::JsonLines,
        );
        let e0 = got[0].as_ref().unwrap_err();
        assert_eq!(e0.line, 1);
        assert!(e0.message.contains("unknown field `colour`"), "{e0}");
        assert_eq!(got[1].as_ref().unwrap_err().line, 2);
        let e2 = got[2].as_ref().unwrap_err();
        assert!(e2.to_string().starts_with("m:3: views:"), "{e2}");
        assert_eq!(got[3].as_ref().unwrap().path, "d.obj");
    }

    #[test]
    fn an_overlong_line_is_skipped_whole() {
        let long = format!("{{\"path\": \"{}\"}}\n", "x".repeat(MAX_LINE_BYTES * 2));
        let got = read(
            &format!("{long}{{\"path\": \"ok.obj\"}}\n"),
            ManifestFormat::JsonLines,
        );
        assert_eq!(got.len(), 2);
        assert!(got[0].as_ref().unwrap_err().message.contains("longer than"));
        let ok = got[1].as_ref().unwrap();
        assert_eq!((ok.line, ok.path.as_str()), (2, "ok.obj"));
    }

    #[test]
    fn csv_with_header_quotes_and_empty_optional_fields() {
        let got = read(
            "path,id,views\n\"a, b.obj\",first,\nc.obj,,cube\nd.obj\n",
            ManifestFormat::Csv,
        );
        let a = got[0].as_ref().unwrap();
        assert_eq!(
            (a.path.as_str(), a.id.as_deref(), a.views),
            ("a, b.obj", Some("first"), None)
        );
        let c = got[1].as_ref().unwrap();
        assert_eq!((c.id.as_deref(), c.views), (None, Some(Views::Cube)));
        assert!(got[2].as_ref().unwrap_err().message.contains("1 fields"));
    }

    #[test]
    fn csv_header_must_name_known_columns_and_a_path() {
        let open = |text: &str| {
            Manifest::from_reader(
                Box::new(std::io::Cursor::new(text.as_bytes().to_vec())),
                "m.csv",
                PathBuf::from("."),
                ManifestFormat::Csv,
            )
            .err()
            .map(|e| e.to_string())
        };
        assert!(open("path,colour\n")
            .unwrap()
            .contains("unknown column \"colour\""));
        assert!(open("id\n").unwrap().contains("no \"path\" column"));
        assert!(open("").unwrap().contains("no header"));
        assert_eq!(open("path, id\n"), None);
    }
}
