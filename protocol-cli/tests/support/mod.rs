//! Helpers of the command's tests: running the `protocol` binary, reading its JSON Lines and
//! the captures' ground truth, loading specs, a deterministic random generator.
#![allow(dead_code)]

use protocol_dynamic::Interpreter;
use serde_json::Value;

/// The registry of bundled specs (`tests/catalogue.toml`).
#[path = "../../../tests/catalogue.rs"]
pub mod catalogue;

/// The registry, read once.
pub fn catalogue() -> &'static catalogue::Catalogue {
    static CATALOGUE: std::sync::OnceLock<catalogue::Catalogue> = std::sync::OnceLock::new();
    CATALOGUE.get_or_init(catalogue::load)
}

/// A string that lives as long as the test binary (the lists below are built once).
fn keep(text: String) -> &'static str {
    Box::leak(text.into_boxed_str())
}

/// A capture: its spec's path, its name and the options `decode` needs.
pub type Capture = (&'static str, &'static str, &'static [&'static str]);

/// Spec, name and the options `decode` needs of every serial capture of `examples/captures/`
/// (`NAME.bin`, with its truth `NAME.truth.jsonl`), as the registry lists them.
pub const CAPTURES: Listed<Capture> = Listed(captures);

fn captures() -> &'static [Capture] {
    static CAPTURES: std::sync::OnceLock<Vec<Capture>> = std::sync::OnceLock::new();
    CAPTURES.get_or_init(|| {
        let catalogue = catalogue();
        catalogue
            .spec
            .iter()
            .flat_map(|e| e.captures.iter().map(move |c| (e, c)))
            .map(|(e, c)| {
                let options: Vec<&'static str> =
                    e.capture_options(c).into_iter().map(keep).collect();
                let options: &'static [&'static str] = Box::leak(options.into_boxed_slice());
                (keep(e.path()), c.name.as_str(), options)
            })
            .collect()
    })
}

/// A list read from the registry once, which a `for` loop, an index and slice methods take as
/// they take the constant slice it stands for (`for (spec, name, how) in CAPTURES`,
/// `CAPTURES[0]`, `SPECS.iter()`).
#[derive(Clone, Copy)]
pub struct Listed<T: 'static>(pub fn() -> &'static [T]);

impl<T> IntoIterator for Listed<T> {
    type Item = &'static T;
    type IntoIter = std::slice::Iter<'static, T>;
    fn into_iter(self) -> Self::IntoIter {
        (self.0)().iter()
    }
}

impl<T> std::ops::Deref for Listed<T> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        (self.0)()
    }
}

/// Each spec a vector suite takes (its name), with each vector file the suite reads and the
/// directions given to the spec's decoder (none when its header tells them), from the registry.
pub fn vector_specs(suite: &str) -> Vec<(&'static str, &'static str, &'static [&'static str])> {
    catalogue()
        .vectors(suite)
        .map(|(e, v)| {
            let directions: Vec<&'static str> = e.directions.iter().map(String::as_str).collect();
            let directions: &'static [&'static str] = Box::leak(directions.into_boxed_slice());
            (e.name.as_str(), v.file.as_str(), directions)
        })
        .collect()
}

/// The interpreter of `specs/NAME.toml`, its messages naming the path as the command's tests
/// pass it (from the workspace root).
pub fn interpreter(name: &str) -> Interpreter {
    interpreter_at(&format!("specs/{name}.toml"))
}

/// The interpreter of the spec at `path`, from the workspace root (as the command's tests
/// pass it, which its messages name).
pub fn interpreter_at(path: &str) -> Interpreter {
    let full = format!("{}/../{path}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&full).unwrap_or_else(|e| panic!("{full}: {e}"));
    Interpreter::from_text(path.to_string(), text)
        .unwrap_or_else(|e| panic!("{path} is invalid:\n{e}"))
}

/// Bytes of hex text.
pub fn unhex(text: &str) -> Vec<u8> {
    protocol_dynamic::parse_hex(text).expect("valid hex")
}

/// xorshift64*: deterministic test data without dependencies.
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn bits(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A number in `lo..=hi`.
    pub fn range(&mut self, lo: u64, hi: u64) -> u64 {
        lo + self.bits() % (hi - lo + 1)
    }

    /// Fills `buf` with random bytes.
    pub fn fill(&mut self, buf: &mut [u8]) {
        for b in buf {
            *b = (self.bits() >> 32) as u8;
        }
    }
}

/// The workspace root: commands run there, so that paths read as a user types them.
pub fn root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the crate is in the workspace")
        .to_path_buf()
}

/// Runs the `protocol` binary in the workspace root, with `stdin` as its input.
pub fn protocol(args: &[&str], stdin: &[u8]) -> std::process::Output {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_protocol"))
        .args(args)
        .current_dir(root())
        .env("NO_COLOR", "1")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let mut input = child.stdin.take().expect("stdin");
    let data = stdin.to_vec();
    // A thread, so that a child that writes much before reading cannot deadlock the test.
    let writer = std::thread::spawn(move || {
        let _ = input.write_all(&data);
    });
    let out = child.wait_with_output().expect("the binary ends");
    let _ = writer.join();
    out
}

/// Text of an output stream.
pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// JSON Lines of an output stream.
pub fn json_lines(bytes: &[u8]) -> Vec<Value> {
    text(bytes)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("not JSON: {l}: {e}")))
        .collect()
}

/// The ground truth the capture script wrote for `examples/captures/NAME`.
pub fn truth(name: &str) -> Vec<Value> {
    let path = root()
        .join("examples/captures")
        .join(format!("{name}.truth.jsonl"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    json_lines(text.as_bytes())
}
