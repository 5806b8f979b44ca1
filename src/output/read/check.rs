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

/// The largest ratio of a buffer's size to its compressed size that LZ4 reaches (a byte of
/// a sequence at most 255 bytes long), and that zstd reaches (an RLE block: 4 bytes make up
/// to 128 KiB).
const MAX_RATIO: [(arrow_ipc::CompressionType, u64); 2] = [
    (arrow_ipc::CompressionType::LZ4_FRAME, 255),
    (arrow_ipc::CompressionType::ZSTD, 32_768),
];

/// Checks the compressed buffers of the Arrow IPC messages in `file` from `start` (0 for a
/// stream, 8 for a file): each one's size once decompressed, which the decoder allocates
/// before it decompresses, must be one its codec can reach from its compressed size. Reads
/// the messages' headers and the first 8 bytes of each compressed buffer only.
pub fn compressed_sizes(file: &mut (impl Read + Seek), start: u64) -> Result<(), String> {
    let mut at = start;
    let mut read = |at: u64, n: usize| -> Option<Vec<u8>> {
        file.seek(SeekFrom::Start(at)).ok()?;
        let mut buf = Vec::new();
        file.by_ref().take(n as u64).read_to_end(&mut buf).ok()?;
        (buf.len() == n).then_some(buf)
    };
    // A file's magic may be padded further, to the writer's alignment (64 bytes).
    while read(at, 8).as_deref() == Some(&[0; 8]) {
        at += 8;
    }
    while let Some(head) = read(at, 8) {
        let len = i32::from_le_bytes([head[4], head[5], head[6], head[7]]);
        let Ok(len) = usize::try_from(len) else { break };
        if head[..4] != [0xff; 4] {
            break;
        }
        let Some(meta) = read(at + 8, len) else {
            break;
        };
        let Ok(message) = arrow_ipc::root_as_message(&meta) else {
            break;
        };
        let Ok(body_len) = u64::try_from(message.bodyLength()) else {
            break;
        };
        let body = at + 8 + len as u64;
        // A record batch's buffers, or a dictionary's (a coded column's texts).
        let batch = message
            .header_as_record_batch()
            .or_else(|| message.header_as_dictionary_batch().and_then(|d| d.data()));
        if let Some(batch) = batch
            && let Some(codec) = batch.compression().map(|c| c.codec())
        {
            let ratio = MAX_RATIO
                .iter()
                .find(|(c, _)| *c == codec)
                .map_or(1, |r| r.1);
            for buffer in batch.buffers().into_iter().flatten() {
                let (Ok(offset), Ok(length)) = (
                    u64::try_from(buffer.offset()),
                    u64::try_from(buffer.length()),
                ) else {
                    continue;
                };
                if length < 8 {
                    continue;
                }
                let Some(prefix) = body.checked_add(offset).and_then(|from| read(from, 8)) else {
                    continue;
                };
                let size = i64::from_le_bytes(prefix.try_into().expect("8 bytes"));
                let most = length.saturating_mul(ratio);
                if size != -1 && (size < 0 || size as u64 > most) {
                    return Err(format!(
                        "a buffer of {length} bytes compressed says it holds {size} bytes, more \
                         than its codec can make of it"
                    ));
                }
            }
        }
        at = body.saturating_add(body_len);
    }
    Ok(())
}
