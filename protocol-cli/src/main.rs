//! The `protocol` command (being built; see the CLI issue).

fn main() {
    eprintln!("protocol: the command-line tool is not built yet; see README.md");
    std::process::exit(2);
}
