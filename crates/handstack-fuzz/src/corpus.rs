//! The grown corpora as archives: each target's corpus is one gzip-compressed tar file,
//! `fuzz/corpus/TARGET.tar.gz`, rather than thousands of small files in the repository.
//!
//! An archive is a flat set of named inputs (libFuzzer names each by the SHA-1 of its bytes).
//! [`write()`] makes it deterministically: entries sorted by name, each a regular file with mode
//! 0644, owner and group 0, time 0, and a gzip header without a time or a file name. So packing
//! the same inputs again gives the same bytes, and the archive changes in git only when the
//! corpus does.
//!
//! `cargo xtask fuzz` unpacks an archive into a work folder with [`unpack`], fuzzes and
//! minimises there, and packs the folder back with [`pack`] (both through the `fuzz-corpus`
//! binary); the replay test reads the archive with [`read`].
//!
//! ```
//! # let dir = std::env::temp_dir().join(format!("handstack-fuzz-doc-{}", std::process::id()));
//! # std::fs::create_dir_all(&dir).unwrap();
//! let archive = dir.join("cdr.tar.gz");
//! let inputs = vec![("b".to_owned(), vec![2u8]), ("a".to_owned(), vec![1u8])];
//! handstack_fuzz::corpus::write(&archive, &inputs).unwrap();
//! let back = handstack_fuzz::corpus::read(&archive).unwrap();
//! assert_eq!(back, [("a".to_owned(), vec![1u8]), ("b".to_owned(), vec![2u8])]);
//! # std::fs::remove_dir_all(&dir).unwrap();
//! ```

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{self, BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};

use flate2::read::GzDecoder;
use flate2::{Compression, GzBuilder};

/// One corpus input: its file name and its bytes.
pub type Entry = (String, Vec<u8>);

/// What went wrong reading or writing a corpus; each names the file or folder.
#[derive(Debug, thiserror::Error)]
pub enum CorpusError {
    /// A file or folder could not be read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file or folder.
        path: PathBuf,
        /// Why.
        source: io::Error,
    },
    /// A file or folder could not be written.
    #[error("cannot write {}: {source}", path.display())]
    Write {
        /// The file or folder.
        path: PathBuf,
        /// Why.
        source: io::Error,
    },
    /// The archive is cut short or is not a gzip-compressed tar file.
    #[error("{} is damaged or cut short (not a whole .tar.gz): {source}", path.display())]
    Damaged {
        /// The archive.
        path: PathBuf,
        /// What the decoder said.
        source: io::Error,
    },
    /// The archive holds something other than a regular file, or a corpus folder holds
    /// something other than regular files (a corpus is flat).
    #[error("{} holds `{name}`, which is not a plain file", path.display())]
    NotAFile {
        /// The archive or folder.
        path: PathBuf,
        /// The entry.
        name: String,
    },
    /// An entry's name is empty, `.` or `..`, holds a path separator or NUL, or is not UTF-8:
    /// unpacking it could write outside the folder.
    #[error("{} holds an entry named `{name}`, which is not a plain file name", path.display())]
    BadName {
        /// The archive, folder or file being written.
        path: PathBuf,
        /// The name, lossily decoded.
        name: String,
    },
    /// Two entries share a name.
    #[error("{} would hold two entries named `{name}`", path.display())]
    Duplicate {
        /// The archive.
        path: PathBuf,
        /// The name.
        name: String,
    },
    /// [`unpack`] writes only into a missing or empty folder, so that the folder ends up
    /// holding exactly the archive's entries.
    #[error("{} is not empty: unpack into a missing or empty folder", path.display())]
    NotEmpty {
        /// The folder.
        path: PathBuf,
    },
}

/// Whether `name` can be a corpus entry: one path component, nothing that escapes a folder.
fn plain_name(name: &str) -> bool {
    !name.is_empty() && name != "." && name != ".." && !name.contains(['/', '\\', '\0'])
}

/// Reads every entry of the archive at `path`, sorted by name.
///
/// # Errors
/// The file cannot be opened ([`CorpusError::Read`]); it is cut short or not a gzip-compressed
/// tar file ([`CorpusError::Damaged`]); it holds something other than regular files with plain,
/// distinct names.
pub fn read(path: &Path) -> Result<Vec<Entry>, CorpusError> {
    let file = File::open(path).map_err(|source| CorpusError::Read {
        path: path.to_owned(),
        source,
    })?;
    let damaged = |source| CorpusError::Damaged {
        path: path.to_owned(),
        source,
    };
    let mut archive = tar::Archive::new(GzDecoder::new(BufReader::new(file)));
    let mut out = BTreeMap::new();
    for entry in archive.entries().map_err(damaged)? {
        let mut entry = entry.map_err(damaged)?;
        let raw = entry.path_bytes().into_owned();
        let name = String::from_utf8_lossy(&raw).into_owned();
        if !entry.header().entry_type().is_file() {
            return Err(CorpusError::NotAFile {
                path: path.to_owned(),
                name,
            });
        }
        if std::str::from_utf8(&raw).is_err() || !plain_name(&name) {
            return Err(CorpusError::BadName {
                path: path.to_owned(),
                name,
            });
        }
        let mut bytes = Vec::new();
        entry.read_to_end(&mut bytes).map_err(damaged)?;
        if out.contains_key(&name) {
            return Err(CorpusError::Duplicate {
                path: path.to_owned(),
                name,
            });
        }
        out.insert(name, bytes);
    }
    // tar stops at its end-of-archive blocks: read the gzip stream to its end so that its
    // length and checksum are checked too.
    io::copy(&mut archive.into_inner(), &mut io::sink()).map_err(damaged)?;
    Ok(out.into_iter().collect())
}

/// Writes `entries` as the archive at `path`, deterministically (see the module docs): the
/// same entries, in any order, give the same bytes. The archive is written beside `path` and
/// renamed over it, so a failed write leaves any previous archive whole.
///
/// # Errors
/// A name that is not a plain file name, two entries with one name, or a failed write.
pub fn write(path: &Path, entries: &[Entry]) -> Result<(), CorpusError> {
    let mut sorted: Vec<&Entry> = entries.iter().collect();
    sorted.sort_by(|a, b| a.0.cmp(&b.0));
    for pair in sorted.windows(2) {
        if pair[0].0 == pair[1].0 {
            return Err(CorpusError::Duplicate {
                path: path.to_owned(),
                name: pair[0].0.clone(),
            });
        }
    }
    if let Some((name, _)) = sorted.iter().find(|(n, _)| !plain_name(n)) {
        return Err(CorpusError::BadName {
            path: path.to_owned(),
            name: name.clone(),
        });
    }
    let mut tmp_name = path.file_name().unwrap_or_default().to_owned();
    tmp_name.push(".tmp");
    let tmp = path.with_file_name(tmp_name);
    let written = write_to(&tmp, &sorted).and_then(|()| std::fs::rename(&tmp, path));
    written.map_err(|source| {
        let _ = std::fs::remove_file(&tmp);
        CorpusError::Write {
            path: path.to_owned(),
            source,
        }
    })
}

/// The archive's bytes, to `path`.
fn write_to(path: &Path, sorted: &[&Entry]) -> io::Result<()> {
    let gz = GzBuilder::new()
        .mtime(0)
        .operating_system(255)
        .write(BufWriter::new(File::create(path)?), Compression::best());
    let mut tar = tar::Builder::new(gz);
    for (name, bytes) in sorted {
        // GNU headers: names past 100 bytes go in a long-name entry.
        let mut header = tar::Header::new_gnu();
        header.set_entry_type(tar::EntryType::Regular);
        header.set_size(bytes.len() as u64);
        header.set_mode(0o644);
        header.set_uid(0);
        header.set_gid(0);
        header.set_mtime(0);
        tar.append_data(&mut header, name, bytes.as_slice())?;
    }
    let mut file = tar.into_inner()?.finish()?.into_inner()?;
    file.flush()?;
    file.sync_all()
}

/// The regular files of the folder `dir` (not recursive), sorted by name.
///
/// # Errors
/// The folder or a file cannot be read; the folder holds a sub-folder or anything else that is
/// not a regular file, or a file whose name is not UTF-8.
pub fn read_dir(dir: &Path) -> Result<Vec<Entry>, CorpusError> {
    let failed = |source| CorpusError::Read {
        path: dir.to_owned(),
        source,
    };
    let mut out = Vec::new();
    for item in std::fs::read_dir(dir).map_err(failed)? {
        let item = item.map_err(failed)?;
        let path = item.path();
        let name = item.file_name();
        let Some(name) = name.to_str().map(str::to_owned) else {
            return Err(CorpusError::BadName {
                path: dir.to_owned(),
                name: name.to_string_lossy().into_owned(),
            });
        };
        if !item.file_type().map_err(failed)?.is_file() {
            return Err(CorpusError::NotAFile {
                path: dir.to_owned(),
                name,
            });
        }
        let bytes = std::fs::read(&path).map_err(|source| CorpusError::Read { path, source })?;
        out.push((name, bytes));
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    Ok(out)
}

/// Packs the regular files of the folder `dir` into the archive at `archive` (replacing it),
/// and returns how many it packed.
///
/// # Errors
/// As [`read_dir`] and [`write()`].
pub fn pack(dir: &Path, archive: &Path) -> Result<usize, CorpusError> {
    let entries = read_dir(dir)?;
    write(archive, &entries)?;
    Ok(entries.len())
}

/// Unpacks the archive at `archive` into the folder `dir`, which must be missing or empty (it
/// is created), and returns how many files it wrote.
///
/// # Errors
/// As [`read`]; `dir` is not empty ([`CorpusError::NotEmpty`]) or cannot be written.
pub fn unpack(archive: &Path, dir: &Path) -> Result<usize, CorpusError> {
    let entries = read(archive)?;
    let unwritable = |path: &Path| {
        let path = path.to_owned();
        move |source| CorpusError::Write { path, source }
    };
    std::fs::create_dir_all(dir).map_err(unwritable(dir))?;
    let mut existing = std::fs::read_dir(dir).map_err(|source| CorpusError::Read {
        path: dir.to_owned(),
        source,
    })?;
    if existing.next().is_some() {
        return Err(CorpusError::NotEmpty {
            path: dir.to_owned(),
        });
    }
    for (name, bytes) in &entries {
        let path = dir.join(name);
        std::fs::write(&path, bytes).map_err(unwritable(&path))?;
    }
    Ok(entries.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh folder under the system's temporary folder, removed on drop.
    struct Scratch(PathBuf);

    impl Scratch {
        fn new(name: &str) -> Self {
            let dir = std::env::temp_dir().join(format!(
                "handstack-fuzz-corpus-{}-{name}",
                std::process::id()
            ));
            let _ = std::fs::remove_dir_all(&dir);
            std::fs::create_dir_all(&dir).unwrap();
            Self(dir)
        }
    }

    impl Drop for Scratch {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    fn inputs() -> Vec<Entry> {
        vec![
            (
                "da39a3ee5e6b4b0d3255bfef95601890afd80709".to_owned(),
                vec![],
            ),
            ("0a".to_owned(), b"\x00\x01\xff binary".to_vec()),
            ("b".repeat(150), vec![7; 5000]),
            ("text".to_owned(), b"Engine: e\n".to_vec()),
        ]
    }

    fn sorted(mut e: Vec<Entry>) -> Vec<Entry> {
        e.sort();
        e
    }

    #[test]
    fn an_archive_reads_back_its_entries_sorted() {
        let s = Scratch::new("round-trip");
        let archive = s.0.join("t.tar.gz");
        write(&archive, &inputs()).unwrap();
        assert_eq!(read(&archive).unwrap(), sorted(inputs()));
        assert!(!s.0.join("t.tar.gz.tmp").exists());
    }

    #[test]
    fn pack_and_unpack_keep_names_and_bytes() {
        let s = Scratch::new("pack");
        let (from, to, archive) = (s.0.join("from"), s.0.join("to"), s.0.join("c.tar.gz"));
        std::fs::create_dir(&from).unwrap();
        for (name, bytes) in inputs() {
            std::fs::write(from.join(name), bytes).unwrap();
        }
        assert_eq!(pack(&from, &archive).unwrap(), 4);
        assert_eq!(unpack(&archive, &to).unwrap(), 4);
        assert_eq!(read_dir(&to).unwrap(), sorted(inputs()));
        // Into a folder that already holds files: refused, nothing mixed in.
        let e = unpack(&archive, &from).unwrap_err();
        assert!(matches!(e, CorpusError::NotEmpty { .. }), "{e}");
    }

    #[test]
    fn the_same_entries_give_the_same_bytes() {
        let s = Scratch::new("determinism");
        let (a, b) = (s.0.join("a.tar.gz"), s.0.join("b.tar.gz"));
        write(&a, &inputs()).unwrap();
        let mut reversed = inputs();
        reversed.reverse();
        write(&b, &reversed).unwrap();
        let bytes = std::fs::read(&a).unwrap();
        assert_eq!(bytes, std::fs::read(&b).unwrap());
        // No time, no file name in the gzip header (flags 0, MTIME 0, OS 255 "unknown").
        assert_eq!(&bytes[..10], &[0x1f, 0x8b, 8, 0, 0, 0, 0, 0, 2, 255]);

        // A folder packed again, with other file times, gives the same archive too.
        let dir = s.0.join("dir");
        unpack(&a, &dir).unwrap();
        let repacked = s.0.join("c.tar.gz");
        pack(&dir, &repacked).unwrap();
        assert_eq!(bytes, std::fs::read(&repacked).unwrap());
    }

    #[test]
    fn entries_are_plain_files_owned_by_nobody_at_time_zero() {
        let s = Scratch::new("headers");
        let archive = s.0.join("h.tar.gz");
        write(&archive, &inputs()).unwrap();
        let file = File::open(&archive).unwrap();
        let mut tar = tar::Archive::new(GzDecoder::new(file));
        let mut names = Vec::new();
        for entry in tar.entries().unwrap() {
            let entry = entry.unwrap();
            let h = entry.header();
            assert_eq!(h.entry_type(), tar::EntryType::Regular);
            assert_eq!(
                (h.mode().unwrap(), h.uid().unwrap(), h.gid().unwrap()),
                (0o644, 0, 0)
            );
            assert_eq!(h.mtime().unwrap(), 0);
            names.push(String::from_utf8(entry.path_bytes().into_owned()).unwrap());
        }
        let mut want: Vec<String> = inputs().into_iter().map(|(n, _)| n).collect();
        want.sort();
        assert_eq!(names, want);
    }

    #[test]
    fn a_cut_archive_is_a_damaged_error_naming_it() {
        let s = Scratch::new("truncated");
        let archive = s.0.join("whole.tar.gz");
        write(&archive, &inputs()).unwrap();
        let bytes = std::fs::read(&archive).unwrap();
        // Cut anywhere: in the entries, in the end-of-archive blocks, in the gzip trailer.
        for keep in [bytes.len() / 2, bytes.len() - 20, bytes.len() - 4, 5] {
            let cut = s.0.join(format!("cut-{keep}.tar.gz"));
            std::fs::write(&cut, &bytes[..keep]).unwrap();
            let e = read(&cut).unwrap_err();
            assert!(matches!(e, CorpusError::Damaged { .. }), "{keep}: {e:?}");
            assert!(e.to_string().contains(&*cut.to_string_lossy()), "{e}");
        }
        let e = read(&s.0.join("missing.tar.gz")).unwrap_err();
        assert!(matches!(e, CorpusError::Read { .. }), "{e:?}");
        assert!(e.to_string().contains("missing.tar.gz"), "{e}");
    }

    #[test]
    fn names_that_leave_the_folder_or_repeat_are_refused() {
        let s = Scratch::new("names");
        let archive = s.0.join("n.tar.gz");
        for bad in ["", ".", "..", "../x", "a/b", "a\\b"] {
            let e = write(&archive, &[(bad.to_owned(), vec![1])]).unwrap_err();
            assert!(matches!(e, CorpusError::BadName { .. }), "{bad:?}: {e:?}");
        }
        let twice = [("x".to_owned(), vec![1]), ("x".to_owned(), vec![2])];
        let e = write(&archive, &twice).unwrap_err();
        assert!(matches!(e, CorpusError::Duplicate { .. }), "{e:?}");
        assert!(!archive.exists());

        // A folder in a corpus folder is not silently left out.
        let dir = s.0.join("nested");
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let e = pack(&dir, &archive).unwrap_err();
        assert!(matches!(e, CorpusError::NotAFile { .. }), "{e:?}");
        assert!(e.to_string().contains("sub"), "{e}");
    }

    #[test]
    fn an_archive_with_a_folder_or_a_path_is_refused() {
        let s = Scratch::new("foreign");
        for (name, kind) in [
            ("sub/", tar::EntryType::Directory),
            ("../escape", tar::EntryType::Regular),
        ] {
            let archive = s.0.join("f.tar.gz");
            let gz = GzBuilder::new().write(File::create(&archive).unwrap(), Compression::fast());
            let mut tar = tar::Builder::new(gz);
            let mut h = tar::Header::new_gnu();
            h.set_entry_type(kind);
            h.set_size(0);
            // `append_data` refuses `..`; write the name into the header by hand.
            h.as_gnu_mut().unwrap().name[..name.len()].copy_from_slice(name.as_bytes());
            h.set_cksum();
            tar.append(&h, io::empty()).unwrap();
            tar.into_inner().unwrap().finish().unwrap();
            let e = read(&archive).unwrap_err();
            assert!(
                matches!(
                    e,
                    CorpusError::NotAFile { .. } | CorpusError::BadName { .. }
                ),
                "{name}: {e:?}"
            );
        }
    }
}
