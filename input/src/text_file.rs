//! Reading one text input file, whatever the path names: only a regular file is opened (a
//! FIFO, a device such as /dev/zero or /dev/urandom, or a directory is refused from its
//! metadata, so reading never blocks or runs without end), at most
//! [`MAX_INPUT_BYTES`](crate::limits::MAX_INPUT_BYTES) are read, the text must be UTF-8
//! (the first invalid byte is named by line and column), and a leading UTF-8 byte-order
//! mark is dropped (editors on Windows write one).

use std::io::Read;
use std::path::{Path, PathBuf};

use crate::limits::MAX_INPUT_BYTES;

/// A text file that cannot be read. `at` is the 1-based line and column, when the error
/// has a place in the file.
#[derive(Clone, Debug, PartialEq)]
pub struct TextFileError {
    pub file: PathBuf,
    pub at: Option<(usize, usize)>,
    pub message: String,
}

impl std::fmt::Display for TextFileError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.at {
            Some((line, column)) => write!(f, "{}:{line}:{column}: {}", self.file.display(), self.message),
            None => write!(f, "{}: {}", self.file.display(), self.message),
        }
    }
}

impl std::error::Error for TextFileError {}

fn kind_of(meta: &std::fs::Metadata) -> &'static str {
    let t = meta.file_type();
    if t.is_dir() {
        return "a directory";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO (named pipe)";
        } else if t.is_char_device() || t.is_block_device() {
            return "a device";
        } else if t.is_socket() {
            return "a socket";
        }
    }
    "not a regular file"
}

/// Reads `path` as UTF-8 text (see the module doc).
pub fn read_text_file(path: &Path) -> Result<String, TextFileError> {
    let err = |at, message: String| TextFileError { file: path.to_path_buf(), at, message };
    let meta = std::fs::metadata(path).map_err(|e| err(None, format!("cannot read: {e}")))?;
    if !meta.is_file() {
        return Err(err(None, format!("cannot read: it is {}, not a regular file", kind_of(&meta))));
    }
    if meta.len() > MAX_INPUT_BYTES {
        return Err(err(None, format!("cannot read: {} bytes, more than romdyn's limit of {MAX_INPUT_BYTES} bytes for an input file", meta.len())));
    }
    let file = std::fs::File::open(path).map_err(|e| err(None, format!("cannot read: {e}")))?;
    let mut bytes = Vec::new();
    // The file may grow while it is read: never more than the limit.
    file.take(MAX_INPUT_BYTES + 1).read_to_end(&mut bytes).map_err(|e| err(None, format!("cannot read: {e}")))?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        return Err(err(None, format!("cannot read: more than romdyn's limit of {MAX_INPUT_BYTES} bytes for an input file")));
    }
    text_from_bytes(bytes).map_err(|(line, column, message)| err(Some((line, column)), message))
}

/// The text of `bytes`: UTF-8 without a leading byte-order mark; an error gives the line
/// and column (in characters) of the first invalid byte.
pub fn text_from_bytes(mut bytes: Vec<u8>) -> Result<String, (usize, usize, String)> {
    if bytes.starts_with(b"\xEF\xBB\xBF") {
        bytes.drain(..3);
    }
    String::from_utf8(bytes).map_err(|e| {
        let valid = e.utf8_error().valid_up_to();
        let good = std::str::from_utf8(&e.as_bytes()[..valid]).unwrap_or_default();
        let line = good.matches('\n').count() + 1;
        let column = good.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        let byte = e.as_bytes()[valid];
        (line, column, format!("byte 0x{byte:02X} is not UTF-8 text (save the file as UTF-8)"))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bom_is_dropped_and_invalid_bytes_are_placed() {
        assert_eq!(text_from_bytes(b"\xEF\xBB\xBFbegin".to_vec()).ok().as_deref(), Some("begin"));
        let (line, column, message) = text_from_bytes(b"ab\ncd\xFFe".to_vec()).unwrap_err();
        assert_eq!((line, column), (2, 3));
        assert!(message.contains("0xFF"), "{message}");
    }

    #[test]
    fn devices_fifos_and_directories_are_refused_without_blocking() {
        for p in ["/dev/zero", "/dev/urandom", "/tmp"] {
            let e = read_text_file(Path::new(p)).unwrap_err().to_string();
            assert!(e.starts_with(&format!("{p}: cannot read: it is ")), "{e}");
        }
        let e = read_text_file(Path::new("/nonexistent/x.mbd")).unwrap_err().to_string();
        assert_eq!(e.matches("os error").count(), 1, "{e}");
    }
}
