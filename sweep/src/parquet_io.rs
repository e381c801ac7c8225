//! Parquet files of a sweep: written so that the bytes depend only on the rows.
//!
//! A sweep's tables are assembled from pieces — chunks of runs finished in any order, or the
//! outputs of shards run on other machines — and must come out byte-identical whichever way
//! they were cut. The Parquet writer's page and row-group boundaries depend on how rows are
//! handed to it, so [`TableWriter`] re-cuts its input into batches of exactly [`FEED_ROWS`]
//! rows (the last one shorter) before writing; row groups hold [`ROW_GROUP_ROWS`] rows;
//! compression is Snappy; the key-value metadata is given by the caller and sorted.

use std::fs::File;
use std::io::{BufWriter, Write as _};
use std::path::{Path, PathBuf};

use arrow_array::RecordBatch;
use arrow_schema::SchemaRef;
use parquet::arrow::ArrowWriter;
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use parquet::basic::Compression;
use parquet::file::metadata::KeyValue;
use parquet::file::properties::WriterProperties;

use crate::error::SweepError;

/// Largest file inside a sweep directory that solsim reads, bytes: 1 TiB. Measured: 43 bytes
/// per run row and 87 per sol row (`solsim sweep scenarios/sol717-719.toml --runs 1000` before its rebuild from the record, five
/// strategies: runs.parquet 216 487 B, sols.parquet 1 307 741 B). A sweep of
/// [`crate::spec::MAX_RUNS`] runs of a 31-sol campaign under five strategies would write some
/// 2 GB of run rows and 135 GB of sol rows. Tables are read a batch at a time and the run table's
/// row count is checked before it is decoded, so the cap bounds the time spent on a sparse or
/// runaway file, not memory.
pub const MAX_TABLE_BYTES: u64 = 1 << 40;

/// Opens a file inside a directory solsim owns (a sweep or shard directory) through the input
/// gate ([`maps::input_file::open_input`]): a regular file of at most `limit_bytes`, checked
/// on the opened descriptor, never a symbolic link (so nothing outside the directory is read
/// through it), never a FIFO or device (which would block or stream forever).
///
/// # Errors
/// [`SweepError::Io`] naming the file and why it was refused.
pub fn open_owned(path: &Path, limit_bytes: u64) -> Result<File, SweepError> {
    maps::input_file::open_input(path, limit_bytes, maps::input_file::Follow::No)
        .map(|(file, _)| file)
        .map_err(|e| SweepError::io(path, "cannot read", e))
}

/// Rows per batch handed to the Parquet writer.
pub const FEED_ROWS: usize = 8192;
/// Rows per row group.
pub const ROW_GROUP_ROWS: usize = 65_536;

/// Writes one table to `path` through a temporary file beside it, renamed into place by
/// [`TableWriter::finish`] after an `fsync`: a reader (or a resumed sweep) sees the whole file
/// or none.
pub struct TableWriter {
    path: PathBuf,
    tmp: PathBuf,
    schema: SchemaRef,
    writer: ArrowWriter<BufWriter<File>>,
    pending: Vec<RecordBatch>,
    pending_rows: usize,
}

/// The temporary name a file is written under before its rename (`.NAME.tmp`).
#[must_use]
pub fn tmp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    path.with_file_name(format!(".{name}.tmp"))
}

impl TableWriter {
    /// Starts writing `path` with `schema` and the key-value `metadata` (written sorted).
    ///
    /// # Errors
    /// The temporary file cannot be created.
    pub fn create(
        path: &Path,
        schema: SchemaRef,
        metadata: &[(String, String)],
    ) -> Result<Self, SweepError> {
        let tmp = tmp_path(path);
        let file = File::create(&tmp).map_err(|e| SweepError::io(&tmp, "cannot create", e))?;
        let mut kv: Vec<KeyValue> = metadata
            .iter()
            .map(|(k, v)| KeyValue::new(k.clone(), v.clone()))
            .collect();
        kv.sort_by(|a, b| a.key.cmp(&b.key));
        let props = WriterProperties::builder()
            .set_compression(Compression::SNAPPY)
            .set_max_row_group_row_count(Some(ROW_GROUP_ROWS))
            .set_key_value_metadata(Some(kv))
            .build();
        let writer = ArrowWriter::try_new(BufWriter::new(file), schema.clone(), Some(props))
            .map_err(|e| SweepError::io(path, "cannot start the Parquet writer for", e))?;
        Ok(Self {
            path: path.to_path_buf(),
            tmp,
            schema,
            writer,
            pending: Vec::new(),
            pending_rows: 0,
        })
    }

    /// Appends rows (any batch size; they are re-cut into [`FEED_ROWS`]).
    ///
    /// # Errors
    /// A batch whose columns differ from the table's, or a write error.
    pub fn push(&mut self, batch: &RecordBatch) -> Result<(), SweepError> {
        if batch.schema().fields() != self.schema.fields() {
            return Err(SweepError::io(
                &self.path,
                "rows with other columns than the table's cannot go into",
                "schema mismatch",
            ));
        }
        let batch = RecordBatch::try_new(self.schema.clone(), batch.columns().to_vec())
            .map_err(|e| SweepError::io(&self.path, "cannot rebuild a batch for", e))?;
        self.pending_rows += batch.num_rows();
        self.pending.push(batch);
        while self.pending_rows >= FEED_ROWS {
            self.feed(FEED_ROWS)?;
        }
        Ok(())
    }

    /// Writes the first `rows` pending rows as one batch.
    fn feed(&mut self, rows: usize) -> Result<(), SweepError> {
        let all = arrow_select::concat::concat_batches(&self.schema, &self.pending)
            .map_err(|e| SweepError::io(&self.path, "cannot concatenate rows for", e))?;
        let head = all.slice(0, rows);
        self.writer
            .write(&head)
            .map_err(|e| SweepError::io(&self.path, "cannot write", e))?;
        let rest = all.num_rows() - rows;
        self.pending = if rest > 0 {
            vec![all.slice(rows, rest)]
        } else {
            Vec::new()
        };
        self.pending_rows = rest;
        Ok(())
    }

    /// Writes the remaining rows, closes the file, `fsync`s it and renames it into place.
    ///
    /// # Errors
    /// A write, sync or rename error.
    pub fn finish(mut self) -> Result<(), SweepError> {
        if self.pending_rows > 0 {
            self.feed(self.pending_rows)?;
        }
        let buffered = self
            .writer
            .into_inner()
            .map_err(|e| SweepError::io(&self.path, "cannot finish", e))?;
        let file = buffered
            .into_inner()
            .map_err(|e| SweepError::io(&self.tmp, "cannot flush", e.error()))?;
        file.sync_all()
            .map_err(|e| SweepError::io(&self.tmp, "cannot sync", e))?;
        drop(file);
        rename_durably(&self.tmp, &self.path)
    }
}

/// Renames `from` to `to` and `fsync`s the directory, so the rename survives a crash.
///
/// # Errors
/// The rename or the directory sync fails.
pub fn rename_durably(from: &Path, to: &Path) -> Result<(), SweepError> {
    std::fs::rename(from, to).map_err(|e| SweepError::io(to, "cannot rename into place", e))?;
    if let Some(dir) = to.parent() {
        let dir = if dir.as_os_str().is_empty() {
            Path::new(".")
        } else {
            dir
        };
        File::open(dir)
            .and_then(|d| d.sync_all())
            .map_err(|e| SweepError::io(dir, "cannot sync the directory", e))?;
    }
    Ok(())
}

/// Writes `bytes` to `path` through a temporary file, `fsync`ed and renamed into place.
///
/// # Errors
/// A write, sync or rename error.
pub fn write_durably(path: &Path, bytes: &[u8]) -> Result<(), SweepError> {
    let tmp = tmp_path(path);
    let mut file = File::create(&tmp).map_err(|e| SweepError::io(&tmp, "cannot create", e))?;
    file.write_all(bytes)
        .and_then(|()| file.sync_all())
        .map_err(|e| SweepError::io(&tmp, "cannot write", e))?;
    drop(file);
    rename_durably(&tmp, path)
}

/// Reads every batch of a Parquet table whose columns must be those of `schema`.
///
/// # Errors
/// The file cannot be opened or decoded, or its columns differ from `schema`'s.
pub fn read_table(path: &Path, schema: &SchemaRef) -> Result<Vec<RecordBatch>, SweepError> {
    table_batches(path, schema, None)?.collect()
}

/// The batches of a Parquet table whose columns must be those of `schema`, read one at a
/// time (a table is never held whole). The file is opened through [`open_owned`]. With
/// `expect_rows`, a table whose footer declares another row count is refused before a row is
/// decoded (what a caller will hold in memory is known before it is read).
///
/// # Errors
/// The file cannot be opened, its columns differ from `schema`'s, or its row count from
/// `expect_rows`; each batch, a decode error.
pub fn table_batches(
    path: &Path,
    schema: &SchemaRef,
    expect_rows: Option<u64>,
) -> Result<impl Iterator<Item = Result<RecordBatch, SweepError>> + use<>, SweepError> {
    let file = open_owned(path, MAX_TABLE_BYTES)?;
    let builder = ParquetRecordBatchReaderBuilder::try_new(file)
        .map_err(|e| SweepError::io(path, "is not a readable Parquet file:", e))?;
    if builder.schema().fields() != schema.fields() {
        let got: Vec<&str> = builder
            .schema()
            .fields()
            .iter()
            .map(|f| f.name().as_str())
            .collect();
        return Err(SweepError::Format {
            path: path.to_path_buf(),
            field: "(columns)".into(),
            expected: format!(
                "the columns of a solsim sweep table ({})",
                schema
                    .fields()
                    .iter()
                    .map(|f| f.name().as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            got: got.join(", "),
        });
    }
    let rows = builder.metadata().file_metadata().num_rows();
    if let Some(want) = expect_rows
        && u64::try_from(rows).ok() != Some(want)
    {
        return Err(SweepError::format(
            path,
            "(rows)",
            format!("{want} rows"),
            format!("{rows} rows"),
        ));
    }
    let reader = builder
        .with_batch_size(FEED_ROWS)
        .build()
        .map_err(|e| SweepError::io(path, "cannot read", e))?;
    let path = path.to_path_buf();
    Ok(reader.map(move |b| b.map_err(|e| SweepError::io(&path, "cannot decode", e))))
}
