//! The rules every file path given on the command line follows, in one place.
//!
//! # Inputs
//!
//! Every input (the OBJ mesh, `--tags`, `--heightmap`) must be a regular file. That is checked
//! from the path's metadata *before* the file is opened, because opening a FIFO for reading
//! blocks until a writer comes (a hang, not an error), and again on the opened file, in case
//! the path was replaced in between. `metadata` follows symbolic links, so a link to a FIFO is
//! refused too. The message names the file and what it is instead ("is a FIFO (named pipe)").
//!
//! # Outputs
//!
//! Checked up front, before any work, so that a long render or export does not end in a
//! refusal:
//! - the folder that will hold the file must exist (it is never created);
//! - a path that names a directory (or ends in `/`) is refused: outputs are files, and the
//!   command does not invent names inside a folder;
//! - a single-file output (`render -o`, `export -o`, `view --screenshot`) may name an existing
//!   device or FIFO, which is then written as Unix tools do (the commands still require the
//!   format's extension);
//! - a prefix output (`bench --out PREFIX` writes `PREFIX.md`, `.csv`, `.json`) must not name
//!   an existing file that is not a regular file: the files would be created beside it
//!   (`/dev/full.md`), which nobody means;
//! - a single-file output that is (or will be) a regular file must be writable: an existing
//!   file this user may not write is refused, and so is a folder that takes no new file (one
//!   is made there and removed), or a name it does not take (too long: a file of that name is
//!   made and removed where none is).
//!
//! A regular file is written whole beside its path and renamed over it only once complete
//! ([`write_output`]): a write that fails (a full disk) or is interrupted (Ctrl-C,
//! [`crate::interrupt`]) leaves what was there before and no temporary file (but for a file
//! that must be written in place, as [`write_output`] says), and an output that names the input
//! replaces it only with a finished file. Several outputs of one command ([`write_outputs`]:
//! `bench --out`'s three) are all written beside their paths before any is put in place.
#![forbid(unsafe_code)]

use std::fs::{File, FileType, Metadata};
use std::path::Path;

/// What a file that is not a regular file is, for messages ("a directory").
pub fn file_kind(t: FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt as _;
    if t.is_file() {
        "a regular file"
    } else if t.is_dir() {
        "a directory"
    } else if t.is_fifo() {
        "a FIFO (named pipe)"
    } else if t.is_socket() {
        "a socket"
    } else if t.is_char_device() {
        "a character device"
    } else if t.is_block_device() {
        "a block device"
    } else {
        "not a regular file"
    }
}

/// Opens the input file `path`, which messages call `what` ("height map"), refusing anything
/// but a regular file without opening it first (see the module notes). Returns the file and its
/// metadata, or one sentence naming the file.
pub fn open_input(path: &Path, what: &str) -> Result<(File, Metadata), String> {
    let shown = path.display();
    let io = |e: std::io::Error| format!("cannot read {what} '{shown}': {e}");
    let not_regular = |t: FileType| {
        format!(
            "{what} '{shown}' is {}, not a regular file: only regular files are read",
            file_kind(t)
        )
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    if !meta.is_file() {
        return Err(not_regular(meta.file_type()));
    }
    let file = File::open(path).map_err(io)?;
    let meta = file.metadata().map_err(io)?;
    if !meta.is_file() {
        return Err(not_regular(meta.file_type()));
    }
    Ok((file, meta))
}

/// How an output path is used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Output {
    /// The path is the file written (a device or FIFO there is written as it is).
    File,
    /// The path is a prefix: files named PREFIX + extension are written beside it.
    Prefix,
    /// A file written only in some runs (the headless `view`'s image, where no window opens):
    /// the rules on the path, not whether it can be written now.
    Fallback,
}

/// Checks the output path that option `option` ("-o", "--out") names, before any work (see the
/// module notes): one sentence naming the path, or Ok.
pub fn check_output(path: &Path, option: &str, kind: Output) -> Result<(), String> {
    let shown = path.display();
    let text = path.as_os_str().to_string_lossy();
    if text.is_empty() {
        return Err(format!("{option} is empty: name a file"));
    }
    let name_it = match kind {
        Output::File | Output::Fallback => "name a file inside it",
        Output::Prefix => {
            "name a prefix inside it (PREFIX gives PREFIX.md, PREFIX.csv and PREFIX.json)"
        }
    };
    if path.is_dir() {
        return Err(format!(
            "{option} '{shown}' is a directory, not a file: {name_it}"
        ));
    }
    if text.ends_with('/') {
        return Err(format!(
            "{option} '{shown}' ends with '/', which names a directory, not a file: {}",
            name_it.replace(" inside it", "")
        ));
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    match std::fs::metadata(parent) {
        Ok(m) if m.is_dir() => {}
        Ok(m) => {
            return Err(format!(
                "{option} '{shown}': '{}' is {}, not a folder",
                parent.display(),
                file_kind(m.file_type())
            ))
        }
        Err(_) => {
            return Err(format!(
                "{option} '{shown}': the folder '{}' does not exist (outputs never create folders)",
                parent.display()
            ))
        }
    }
    if kind == Output::File {
        return check_replaceable(path, option);
    }
    if kind == Output::Prefix {
        if let Ok(m) = std::fs::metadata(path) {
            if !m.is_file() {
                return Err(format!(
                    "{option} '{shown}' is {}: {option} takes a prefix, and PREFIX.md, PREFIX.csv and PREFIX.json would be created beside it",
                    file_kind(m.file_type())
                ));
            }
        }
        // The files it writes: any that exists must be a file to replace, and each must be
        // writable as a single file is (a folder that takes no files, as /proc/self, fails here
        // rather than after the run).
        for ext in ["md", "csv", "json"] {
            // Built from the path's own bytes, as the files are named when written (a name
            // that is not UTF-8 stays itself).
            let mut file = path.as_os_str().to_owned();
            file.push(format!(".{ext}"));
            let file = std::path::PathBuf::from(file);
            if let Ok(m) = std::fs::metadata(&file) {
                if !m.is_file() {
                    return Err(format!(
                        "{option} '{shown}' would write '{}', which is {}, not a file",
                        file.display(),
                        file_kind(m.file_type())
                    ));
                }
            }
            check_replaceable(&file, option)?;
        }
    }
    Ok(())
}

/// Where a regular-file output is really written: the name a chain of symbolic links ends at
/// (the links are kept; a dangling one's file is created), else `path` itself; `None` for a
/// device or FIFO, written as it is. A chain that loops (or runs past 40 links, as the kernel
/// counts) is an error, as opening it would be.
fn regular_target(path: &Path) -> std::io::Result<Option<std::path::PathBuf>> {
    if std::fs::metadata(path).is_ok_and(|m| !m.is_file()) {
        return Ok(None);
    }
    let mut target = path.to_path_buf();
    // The kernel follows up to 40 links: 40 reads, then the file they lead to.
    for _ in 0..=40 {
        match std::fs::read_link(&target) {
            Ok(to) => target = target.parent().unwrap_or(Path::new(".")).join(to),
            Err(_) => return Ok(Some(target)),
        }
    }
    Err(std::io::Error::other("too many levels of symbolic links"))
}

/// A new temporary file beside `target`, made exclusively (never through a link another user
/// left there), with a short name whatever `target`'s length, and registered for removal if
/// the process is interrupted before it is made, so that no signal, on whichever thread it
/// comes, can leave it behind (a name registered but not made removes nothing: it is this
/// process's own, `.meshrefine-PID-...`).
fn temporary_registered(target: &Path) -> std::io::Result<(std::path::PathBuf, File, Temporary)> {
    use std::hash::{BuildHasher as _, Hasher as _};
    crate::interrupt::install();
    let folder = match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut last = None;
    for attempt in 0..16u64 {
        let mut h = std::collections::hash_map::RandomState::new().build_hasher();
        h.write_u64(attempt);
        let name = format!(
            ".meshrefine-{}-{:08x}.tmp",
            std::process::id(),
            h.finish() as u32
        );
        let tmp = folder.join(name);
        let mut guard = Temporary::new(&tmp);
        match File::options()
            .read(true)
            .write(true)
            .create_new(true)
            .open(&tmp)
        {
            Ok(file) => return Ok((tmp, file, guard)),
            Err(e) => {
                // Not made here: not removed either.
                guard.0 = None;
                if e.kind() != std::io::ErrorKind::AlreadyExists {
                    return Err(e);
                }
                last = Some(e);
            }
        }
    }
    Err(last.unwrap_or_else(|| std::io::Error::other("no temporary file name was free")))
}

/// Removes the temporary file when dropped (an error or a panic on the way), unless kept (the
/// path taken); an interrupting signal removes it meanwhile ([`crate::interrupt`]).
struct Temporary(Option<std::path::PathBuf>, crate::interrupt::Registered);

impl Temporary {
    fn new(tmp: &Path) -> Self {
        Self(Some(tmp.to_path_buf()), crate::interrupt::register(tmp))
    }
}

impl Drop for Temporary {
    fn drop(&mut self) {
        // Removed first, then forgotten: a signal in between unlinks a name already gone.
        if let Some(p) = self.0.take() {
            let _ = std::fs::remove_file(p);
        }
        self.1.clear();
    }
}

/// Whether an existing output `old` is written in place rather than replaced by a rename
/// ([`write_output`]): another user's file (a rename would make it ours) or one with other
/// hard links (a rename would part them); `mine` is the owner of a file this process made.
fn written_in_place(old: &std::fs::Metadata, mine: u32) -> bool {
    use std::os::unix::fs::MetadataExt as _;
    old.uid() != mine || old.nlink() > 1
}

/// Whether the single-file output `path` can be written (module notes): one sentence if not.
/// The folder must take a new file (one is made and removed); an existing file that will be
/// written in place must open for writing (only then: opening a file for writing tells the
/// programs that watch it that it changed).
fn check_replaceable(path: &Path, option: &str) -> Result<(), String> {
    let shown = path.display();
    let cannot = |e: std::io::Error| format!("{option} '{shown}': cannot write there: {e}");
    let Some(target) = regular_target(path).map_err(cannot)? else {
        return Ok(());
    };
    if target != path {
        // A link whose file would be made in a folder that is not there.
        let folder = target.parent().filter(|p| !p.as_os_str().is_empty());
        let folder = folder.unwrap_or(Path::new("."));
        let is = match std::fs::metadata(folder) {
            Ok(m) if m.is_dir() => None,
            Ok(m) => Some(format!("is {}, not a folder", file_kind(m.file_type()))),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                Some("does not exist (outputs never create folders)".to_string())
            }
            Err(e) => Some(format!("cannot be read: {e}")),
        };
        if let Some(is) = is {
            return Err(format!(
                "{option} '{shown}' is a link to '{}', whose folder '{}' {is}",
                target.display(),
                folder.display()
            ));
        }
    }
    let (tmp, probe, mut made) = temporary_registered(&target).map_err(cannot)?;
    let mine = std::os::unix::fs::MetadataExt::uid(&probe.metadata().map_err(cannot)?);
    let old = std::fs::metadata(&target).ok();
    if old.is_none() {
        // None is there yet: the probe goes where the output will, as the output will (a
        // rename, under the output's own name: one the folder does not take, too long say,
        // fails here), registered there first so that a signal leaves nothing behind.
        let mut placed = Temporary::new(&target);
        if let Err(e) = std::fs::rename(&tmp, &target) {
            placed.0 = None;
            return Err(cannot(e));
        }
        made.0 = None;
        made = placed;
    }
    // And it must go again: a folder that takes files but lets none go (append-only) would
    // keep every temporary file.
    if let Some(path) = made.0.take() {
        std::fs::remove_file(&path).map_err(|e| {
            format!(
                "{option} '{shown}': cannot write there: a file made there cannot be removed: {e}"
            )
        })?;
    }
    drop(made);
    let Some(old) = old else {
        return Ok(());
    };
    // A read-only file is not replaced, as it would not be written (root's excepted).
    if old.permissions().readonly() && mine != 0 {
        return Err(format!("{option} '{shown}' is a read-only file"));
    }
    if written_in_place(&old, mine) {
        File::options()
            .write(true)
            .open(&target)
            .map_err(|e| format!("{option} '{shown}' is a file this user may not write: {e}"))?;
    }
    Ok(())
}

/// Writes the output file `path` with `write` (module notes). A regular file (or none yet) is
/// written to a new temporary file beside it, flushed to the disk and renamed over it only once
/// whole, with the old file's permissions (less set-user and set-group ID) and group; on any
/// error (or a panic) the temporary file is removed and what `path` held stays. Where a rename
/// would change more than the contents (the old file is another user's, has other hard links,
/// or has a group this user may not give) or cannot be done (across file systems, a file
/// mounted on its own), the finished file is copied into the old one, which is not atomic: a
/// failure while copying leaves it partly written. A device or FIFO is written directly.
pub fn write_output(
    path: &Path,
    write: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    match stage_output(path, write)? {
        Some(staged) => staged.commit(),
        None => Ok(()),
    }
}

/// Several outputs, all or none as far as the file system allows: each file is written whole
/// beside its place first ([`write_output`]; each temporary registered for removal if the
/// process is interrupted), and only once every one is are they put in place, so a failed
/// write (a full disk) leaves every old file as it was. Putting them in place is renames, which
/// fail only for a name the folder does not take ([`check_output`] refuses it up front), but
/// where a file must be copied into its place ([`write_output`]: another user's, one with other
/// hard links, another file system) a failure while copying, or an interruption between the
/// renames, can leave some files of each run. Each error names its file.
pub fn write_outputs(files: &[(&Path, &[u8])]) -> std::io::Result<()> {
    let named = |path: &Path, e: std::io::Error| {
        std::io::Error::new(e.kind(), format!("'{}': {e}", path.display()))
    };
    let mut staged = Vec::new();
    for &(path, bytes) in files {
        let s = stage_output(path, |w| w.write_all(bytes)).map_err(|e| named(path, e))?;
        staged.push((path, s));
    }
    // No signal between the renames: the set is put in place whole (a signal that comes then
    // ends the process right after). Held back on this thread, the one that takes them where
    // the commands write their outputs: after their GPU work, the device and its threads gone.
    crate::interrupt::deferred(|| {
        for (path, s) in staged {
            if let Some(s) = s {
                s.commit().map_err(|e| named(path, e))?;
            }
        }
        Ok(())
    })
}

/// An output written whole to a temporary file beside its place ([`stage_output`]), removed
/// unless [`Staged::commit`] puts it there.
struct Staged {
    target: std::path::PathBuf,
    guard: Temporary,
    file: File,
}

/// [`write_output`]'s first half: a regular file (or none yet) is written to a temporary file
/// beside it and flushed to the disk (returned, to put in place); a device or FIFO is written
/// directly (`None`).
fn stage_output(
    path: &Path,
    write: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
) -> std::io::Result<Option<Staged>> {
    use std::io::Write as _;
    let Some(target) = regular_target(path)? else {
        let mut w = std::io::BufWriter::with_capacity(1 << 20, File::create(path)?);
        write(&mut w)?;
        w.flush()?;
        return Ok(None);
    };
    let (_, file, guard) = temporary_registered(&target)?;
    let mut w = std::io::BufWriter::with_capacity(1 << 20, file);
    write(&mut w)?;
    let file = w.into_inner().map_err(|e| e.into_error())?;
    // A full disk may only say so when the data reaches it.
    file.sync_all()?;
    Ok(Some(Staged {
        target,
        guard,
        file,
    }))
}

impl Staged {
    /// Puts the file in its place: renamed over the old one with its permissions, or copied
    /// into it where a rename would change more than the contents or cannot be done.
    fn commit(mut self) -> std::io::Result<()> {
        use std::os::unix::fs::{MetadataExt as _, PermissionsExt as _};
        let target = &self.target;
        let old = std::fs::metadata(target).ok();
        let mine = self.file.metadata()?.uid();
        if old.as_ref().is_some_and(|m| written_in_place(m, mine)) {
            return copy_into(&mut self.file, target);
        }
        if let Some(m) = &old {
            // The old file's group too, where this user may give it (else written in place,
            // so that the group keeps what it could do).
            if m.gid() != self.file.metadata()?.gid()
                && std::os::unix::fs::fchown(&self.file, None, Some(m.gid())).is_err()
            {
                return copy_into(&mut self.file, target);
            }
            let mode = m.permissions().mode() & !0o6000;
            self.file
                .set_permissions(std::fs::Permissions::from_mode(mode))?;
        }
        let tmp = self
            .guard
            .0
            .clone()
            .expect("a staged file has its temporary");
        match std::fs::rename(&tmp, target) {
            Ok(()) => {
                self.guard.0 = None;
                Ok(())
            }
            // EBUSY (a file mounted on its own), EXDEV (another file system).
            Err(e) if matches!(e.raw_os_error(), Some(16 | 18)) => {
                copy_into(&mut self.file, target)
            }
            Err(e) => Err(e),
        }
    }
}

/// Copies `from` (read from its start) into the existing or new file `target` without
/// truncating it first: written, cut to length, flushed to the disk.
fn copy_into(from: &mut File, target: &Path) -> std::io::Result<()> {
    use std::io::Seek as _;
    from.rewind()?;
    let mut to = File::options()
        .write(true)
        .create(true)
        .truncate(false)
        .open(target)?;
    let written = std::io::copy(from, &mut to)?;
    to.set_len(written)?;
    to.sync_all()
}

/// `text` with its control characters escaped (`\u{1b}`, `\n`): a warning or error stays one
/// line and writes nothing a terminal would act on, whatever a file or a path held. So are the
/// characters that show nothing or reorder what follows ([`unseen`]): a byte-order mark inside
/// a file (two files joined) is quoted as `'\u{feff}f'`, not as an `'f'` said to be no statement.
pub fn printable(text: &str) -> std::borrow::Cow<'_, str> {
    let hidden = |c: char| c.is_control() || unseen(c);
    if !text.chars().any(hidden) {
        return text.into();
    }
    (text.chars())
        .map(|c| match hidden(c) {
            true => c.escape_default().to_string(),
            false => c.to_string(),
        })
        .collect::<String>()
        .into()
}

/// The format characters a terminal shows nothing for, or that reorder or break the text after
/// them: the soft hyphen, the Arabic letter mark, the Mongolian vowel separator, zero-width
/// spaces and joiners, the line and paragraph separators, the direction marks, embeddings,
/// overrides and isolates, the invisible operators, the byte-order mark (zero-width no-break
/// space), the interlinear annotation characters and the tags.
pub fn unseen(c: char) -> bool {
    matches!(
        c,
        '\u{ad}'
            | '\u{61c}'
            | '\u{180e}'
            | '\u{200b}'..='\u{200f}'
            | '\u{2028}'..='\u{202e}'
            | '\u{2060}'..='\u{2064}'
            | '\u{2066}'..='\u{2069}'
            | '\u{feff}'
            | '\u{fff9}'..='\u{fffb}'
            | '\u{e0000}'..='\u{e007f}'
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Control characters and the characters a terminal shows nothing for are escaped; other
    /// text, accented or not, is kept.
    #[test]
    fn unseen_characters_are_escaped() {
        assert_eq!(printable("caf\u{e9}.obj"), "caf\u{e9}.obj");
        assert_eq!(printable("\u{feff}f"), "\\u{feff}f");
        assert_eq!(printable("a\u{202e}b\u{200b}c"), "a\\u{202e}b\\u{200b}c");
        assert_eq!(printable("x\ny\u{1b}"), "x\\ny\\u{1b}");
        assert_eq!(printable("p\u{2028}q\u{e0041}"), "p\\u{2028}q\\u{e0041}");
    }

    /// Several outputs are put in place only once every one is written: where the last cannot
    /// be written (no folder for it), the others keep what an earlier run wrote, no temporary
    /// file is left, and the error names the file; where all can, all are replaced. A name
    /// too long for its folder, which only putting the file in place would find, is refused by
    /// the check before any work.
    #[test]
    fn outputs_written_together_are_all_replaced_or_none() {
        let d = dir().join("write-outputs");
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        let (md, csv) = (d.join("run.md"), d.join("run.csv"));
        let lost = d.join("gone").join("run.json");
        for f in [&md, &csv] {
            std::fs::write(f, "earlier run").unwrap();
        }
        let e = write_outputs(&[(&md, b"new"), (&csv, b"new"), (&lost, b"new")]).unwrap_err();
        assert!(
            e.to_string().contains(&format!("'{}'", lost.display())),
            "{e}"
        );
        for f in [&md, &csv] {
            assert_eq!(std::fs::read_to_string(f).unwrap(), "earlier run");
        }
        assert_eq!(
            std::fs::read_dir(&d).unwrap().count(),
            2,
            "a temporary file left"
        );
        let long = d.join(format!("{}.json", "a".repeat(251)));
        let refused = check_output(&long, "--out", Output::File).unwrap_err();
        assert!(refused.contains("cannot write there"), "{refused}");
        let json = d.join("run.json");
        write_outputs(&[(&md, b"new"), (&csv, b"new"), (&json, b"new")]).unwrap();
        for f in [&md, &csv, &json] {
            assert_eq!(std::fs::read_to_string(f).unwrap(), "new");
        }
        assert!(check_output(&d.join("fresh.png"), "-o", Output::File).is_ok());
        assert!(!d.join("fresh.png").exists(), "the check left its file");
    }

    /// A replaced file keeps its group (renamed over with the group given to the new file, or
    /// written in place where this user may not give it); a chain of 40 symbolic links, as
    /// many as the kernel follows, is written through, one more is refused; a prefix that is
    /// not UTF-8 is checked under its own bytes (a folder named as its .csv refused up front).
    #[test]
    fn outputs_keep_their_group_follow_40_links_and_any_bytes() {
        use std::os::unix::ffi::OsStrExt as _;
        use std::os::unix::fs::MetadataExt as _;
        let d = dir().join("output-group-links");
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        let grouped = d.join("g.obj");
        std::fs::write(&grouped, "old").unwrap();
        // Another group than a new file's, where this user may give one (root in CI).
        if std::os::unix::fs::chown(&grouped, None, Some(65534)).is_ok() {
            write_output(&grouped, |w| w.write_all(b"new")).unwrap();
            let m = std::fs::metadata(&grouped).unwrap();
            assert_eq!(
                (m.gid(), std::fs::read_to_string(&grouped).unwrap().as_str()),
                (65534, "new")
            );
        }
        let end = d.join("end.obj");
        std::fs::write(&end, "old").unwrap();
        let mut last = end.clone();
        for i in 0..41 {
            let link = d.join(format!("l{i}.obj"));
            std::os::unix::fs::symlink(last.file_name().unwrap(), &link).unwrap();
            last = link;
            if i == 39 {
                // 40 links to the file.
                assert!(check_output(&last, "-o", Output::File).is_ok());
                write_output(&last, |w| w.write_all(b"through 40")).unwrap();
                assert_eq!(std::fs::read_to_string(&end).unwrap(), "through 40");
            }
        }
        let refused = check_output(&last, "-o", Output::File).unwrap_err();
        assert!(
            refused.contains("too many levels of symbolic links"),
            "{refused}"
        );
        // Two links naming each other: a loop, refused the same way, and nothing written.
        std::os::unix::fs::symlink("b.obj", d.join("a.obj")).unwrap();
        std::os::unix::fs::symlink("a.obj", d.join("b.obj")).unwrap();
        let refused = check_output(&d.join("a.obj"), "-o", Output::File).unwrap_err();
        assert!(
            refused.contains("too many levels of symbolic links"),
            "{refused}"
        );
        assert!(write_output(&d.join("a.obj"), |w| w.write_all(b"x")).is_err());
        assert!(std::fs::symlink_metadata(d.join("a.obj"))
            .unwrap()
            .is_symlink());
        let prefix = d.join(std::ffi::OsStr::from_bytes(b"q\xff"));
        std::fs::create_dir(d.join(std::ffi::OsStr::from_bytes(b"q\xff.csv"))).unwrap();
        let refused = check_output(&prefix, "--out", Output::Prefix).unwrap_err();
        assert!(refused.contains("which is a directory"), "{refused}");
    }

    /// A write that fails part way, or panics, leaves the file as it was and no temporary file;
    /// one that ends replaces it whole, with its permissions, through a symbolic link (the
    /// link kept), and a dangling link gets the file it names; a path through a regular file is
    /// refused up front.
    #[test]
    fn outputs_are_replaced_whole_or_not_at_all() {
        use std::os::unix::fs::PermissionsExt as _;
        let d = dir().join("write-output");
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(d.join("sub")).unwrap();
        let names = |d: &Path| -> Vec<String> {
            let mut v: Vec<String> = std::fs::read_dir(d)
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect();
            v.sort();
            v
        };
        let out = d.join("out.obj");
        std::fs::write(&out, "precious").unwrap();
        std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o640)).unwrap();
        let e = write_output(&out, |w| {
            w.write_all(b"half a mesh")?;
            Err(std::io::Error::other("no space left"))
        })
        .unwrap_err();
        assert_eq!(e.to_string(), "no space left");
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "precious");
        let panicked = std::panic::catch_unwind(|| {
            let _ = write_output(&out, |w| {
                w.write_all(b"half a mesh")?;
                panic!("a bug in the writer")
            });
        });
        assert!(panicked.is_err());
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "precious");
        assert_eq!(names(&d), ["out.obj", "sub"]);
        write_output(&out, |w| w.write_all(b"whole")).unwrap();
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "whole");
        let mode = std::fs::metadata(&out).unwrap().permissions().mode();
        assert_eq!(mode & 0o777, 0o640);
        let link = d.join("link.obj");
        std::os::unix::fs::symlink("out.obj", &link).unwrap();
        check_output(&link, "-o", Output::File).unwrap();
        write_output(&link, |w| w.write_all(b"through")).unwrap();
        assert!(std::fs::symlink_metadata(&link).unwrap().is_symlink());
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "through");
        let nowhere = d.join("nowhere.obj");
        std::os::unix::fs::symlink("missing/x.obj", &nowhere).unwrap();
        let e = check_output(&nowhere, "-o", Output::File).unwrap_err();
        let missing = d.join("missing");
        assert_eq!(
            e,
            format!(
                "-o '{}' is a link to '{}', whose folder '{}' does not exist (outputs never create folders)",
                nowhere.display(),
                missing.join("x.obj").display(),
                missing.display()
            )
        );
        std::fs::remove_file(&nowhere).unwrap();
        // Through a regular file: no folder at all.
        std::os::unix::fs::symlink("out.obj/x.obj", &nowhere).unwrap();
        let e = check_output(&nowhere, "-o", Output::File).unwrap_err();
        assert!(
            e.ends_with("out.obj' is a regular file, not a folder"),
            "{e}"
        );
        std::fs::remove_file(&nowhere).unwrap();
        let dangling = d.join("dangling.obj");
        std::os::unix::fs::symlink("sub/made.obj", &dangling).unwrap();
        write_output(&dangling, |w| w.write_all(b"new")).unwrap();
        assert!(std::fs::symlink_metadata(&dangling).unwrap().is_symlink());
        assert_eq!(
            std::fs::read_to_string(d.join("sub/made.obj")).unwrap(),
            "new"
        );
        assert_eq!(names(&d), ["dangling.obj", "link.obj", "out.obj", "sub"]);
        // A device is written as it is.
        write_output(Path::new("/dev/null"), |w| w.write_all(b"x")).unwrap();
        let e = check_output(&out.join("x.obj"), "-o", Output::File).unwrap_err();
        assert!(
            e.ends_with("out.obj' is a regular file, not a folder"),
            "{e}"
        );
        std::fs::remove_dir_all(&d).unwrap();
    }

    /// A file with another hard link is written in place (both names see the new bytes, the
    /// link kept); a replaced file keeps its permissions less set-user and set-group ID; a
    /// read-only file is refused up front, except to root, who may write it.
    #[test]
    fn links_special_bits_and_read_only_files() {
        use std::os::unix::fs::{MetadataExt as _, PermissionsExt as _};
        let d = dir().join("links-and-bits");
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        let (out, other) = (d.join("out.obj"), d.join("other-name.obj"));
        std::fs::write(&out, "old").unwrap();
        std::fs::hard_link(&out, &other).unwrap();
        check_output(&out, "-o", Output::File).unwrap();
        write_output(&out, |w| w.write_all(b"new")).unwrap();
        assert_eq!(std::fs::read_to_string(&other).unwrap(), "new");
        assert_eq!(std::fs::metadata(&out).unwrap().nlink(), 2);
        assert_eq!(
            std::fs::metadata(&out).unwrap().ino(),
            std::fs::metadata(&other).unwrap().ino()
        );
        let special = d.join("special.obj");
        std::fs::write(&special, "old").unwrap();
        std::fs::set_permissions(&special, std::fs::Permissions::from_mode(0o6755)).unwrap();
        // Both bits are set (the kernel keeps set-group ID only for a group of the owner's).
        let mode = std::fs::metadata(&special).unwrap().permissions().mode();
        assert_eq!(mode & 0o7777, 0o6755, "{mode:o}");
        write_output(&special, |w| w.write_all(b"new")).unwrap();
        let mode = std::fs::metadata(&special).unwrap().permissions().mode();
        assert_eq!(mode & 0o7777, 0o755, "{mode:o}");
        let read_only = d.join("read-only.obj");
        std::fs::write(&read_only, "old").unwrap();
        std::fs::set_permissions(&read_only, std::fs::Permissions::from_mode(0o444)).unwrap();
        let checked = check_output(&read_only, "-o", Output::File);
        let root = std::fs::metadata(&d).unwrap().uid() == 0;
        match checked {
            Ok(()) => assert!(root, "a read-only file was taken"),
            Err(e) => {
                assert!(!root, "{e}");
                assert!(e.ends_with("read-only.obj' is a read-only file"), "{e}");
            }
        }
        std::fs::remove_dir_all(&d).unwrap();
    }

    fn dir() -> std::path::PathBuf {
        let d = std::env::temp_dir().join("meshrefine-paths-test");
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn inputs_must_be_regular_files() {
        let d = dir();
        let f = d.join("file.txt");
        std::fs::write(&f, "x").unwrap();
        assert!(open_input(&f, "tags file").is_ok());
        let e = open_input(&d, "height map").unwrap_err();
        assert!(
            e.starts_with("height map '") && e.contains("is a directory"),
            "{e}"
        );
        let e = open_input(&d.join("missing"), "tags file").unwrap_err();
        assert!(e.starts_with("cannot read tags file '"), "{e}");
        let e = open_input(Path::new("/dev/null"), "height map").unwrap_err();
        assert!(e.contains("is a character device"), "{e}");
    }

    #[test]
    fn outputs_need_an_existing_folder_and_a_file_name() {
        let d = dir();
        let ok = d.join("x.png");
        assert_eq!(check_output(&ok, "-o", Output::File), Ok(()));
        assert_eq!(check_output(Path::new("x.png"), "-o", Output::File), Ok(()));
        for kind in [Output::File, Output::Prefix] {
            let e = check_output(&d, "-o", kind).unwrap_err();
            assert!(e.contains("is a directory, not a file"), "{e}");
            let slash = format!("{}/", d.join("sub").display());
            let e = check_output(Path::new(&slash), "--out", kind).unwrap_err();
            assert!(e.contains("ends with '/', which names a directory"), "{e}");
            let slash = format!("{}/", d.display());
            let e = check_output(Path::new(&slash), "--out", kind).unwrap_err();
            assert!(e.contains("is a directory, not a file"), "{e}");
            let e = check_output(&d.join("nodir/x"), "-o", kind).unwrap_err();
            assert!(
                e.contains("the folder '") && e.contains("nodir' does not exist"),
                "{e}"
            );
        }
        // A device is written as it is by a single-file output, never beside by a prefix.
        assert_eq!(
            check_output(Path::new("/dev/null"), "-o", Output::File),
            Ok(())
        );
        let e = check_output(Path::new("/dev/null"), "--out", Output::Prefix).unwrap_err();
        assert!(e.contains("is a character device"), "{e}");
        let e = check_output(Path::new("/dev/null/x"), "-o", Output::File).unwrap_err();
        assert!(e.contains("is a character device, not a folder"), "{e}");
        // A prefix whose PREFIX.json is a directory would fail after the whole benchmark.
        let prefix = d.join("results");
        std::fs::create_dir_all(d.join("results.json")).unwrap();
        let e = check_output(&prefix, "--out", Output::Prefix).unwrap_err();
        assert!(
            e.contains("would write '") && e.contains("results.json', which is a directory"),
            "{e}"
        );
        std::fs::write(d.join("results.md"), "old").unwrap();
        std::fs::remove_dir(d.join("results.json")).unwrap();
        assert_eq!(check_output(&prefix, "--out", Output::Prefix), Ok(()));
    }
}
