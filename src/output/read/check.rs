//! Cheap checks of a file's sizes before it is decoded: every length and offset its
//! metadata gives that the decoders would read or allocate by must lie within the file, so
//! that a damaged length is refused rather than asking for terabytes (an abort, not a
//! panic: no guard catches it).

use parquet::file::metadata::ParquetMetaData;
use std::io::{Read, Seek, SeekFrom};

/// Bytes before the first message of an Arrow IPC file: its magic `ARROW1`, padded to 8.
const ARROW_HEAD: u64 = 8;
/// Bytes after the footer of an Arrow IPC file: the footer's length (4) and the magic (6).
const ARROW_TAIL: u64 = 10;

/// Checks the footer of an Arrow IPC file of `len` bytes read through `file`: its length,
/// its flatbuffer, and that each batch and dictionary it lists lies between the magic and
/// the footer. The error says what is wrong.
pub fn arrow_file(file: &mut (impl Read + Seek), len: u64) -> Result<(), String> {
    if len < ARROW_HEAD + ARROW_TAIL {
        return Err(format!("{len} bytes, too short for an Arrow IPC file"));
    }
    let mut tail = [0u8; ARROW_TAIL as usize];
    file.seek(SeekFrom::Start(len - ARROW_TAIL))
        .and_then(|_| file.read_exact(&mut tail))
        .map_err(|e| e.to_string())?;
    if &tail[4..] != b"ARROW1" {
        return Err("no ARROW1 at its end: it is cut off or not an Arrow IPC file".into());
    }
    let footer_len = i32::from_le_bytes([tail[0], tail[1], tail[2], tail[3]]);
    let room = len - ARROW_HEAD - ARROW_TAIL;
    let footer_len = u64::try_from(footer_len)
        .ok()
        .filter(|n| (1..=room).contains(n))
        .ok_or_else(|| format!("its footer's length {footer_len} is not within its {len} bytes"))?;
    let mut footer = vec![0u8; footer_len as usize];
    let footer_start = len - ARROW_TAIL - footer_len;
    file.seek(SeekFrom::Start(footer_start))
        .and_then(|_| file.read_exact(&mut footer))
        .map_err(|e| e.to_string())?;
    let footer = arrow_ipc::root_as_footer(&footer).map_err(|e| format!("its footer: {e}"))?;
    let blocks = footer.recordBatches().into_iter().flatten();
    for block in blocks.chain(footer.dictionaries().into_iter().flatten()) {
        let (offset, meta, body) = (block.offset(), block.metaDataLength(), block.bodyLength());
        let end = offset
            .checked_add(i64::from(meta))
            .and_then(|e| e.checked_add(body));
        let within = offset >= ARROW_HEAD as i64
            && meta > 0
            && body >= 0
            && end.is_some_and(|e| e <= footer_start as i64);
        if !within {
            return Err(format!(
                "its footer lists a batch of {meta} + {body} bytes at byte {offset}, outside \
                 bytes {ARROW_HEAD} to {footer_start}"
            ));
        }
    }
    Ok(())
}

/// Checks that every column chunk the Parquet metadata `meta` lists lies within the file's
/// `len` bytes.
pub fn parquet_chunks(meta: &ParquetMetaData, len: u64) -> Result<(), String> {
    for (g, group) in meta.row_groups().iter().enumerate() {
        for column in group.columns() {
            let start = column
                .dictionary_page_offset()
                .unwrap_or_else(|| column.data_page_offset());
            let size = column.compressed_size();
            let end = start.checked_add(size);
            let within = start >= 4 && size >= 0 && end.is_some_and(|e| e as u64 <= len);
            if !within {
                return Err(format!(
                    "row group {g} lists column {} with {size} bytes at byte {start}, outside \
                     its {len} bytes",
                    column.column_path()
                ));
            }
        }
    }
    Ok(())
}
