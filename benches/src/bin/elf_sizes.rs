//! Prints the `.text` and `.rodata` sizes of ELF files (any architecture, such as the
//! `thumbv7em-none-eabihf` firmware of `benches/footprint.sh`), as a Markdown table.
//!
//! Usage: `elf-sizes [--baseline NAME=PATH] NAME=PATH...`. Each row gives a file's sizes, their
//! sum, the ratio of that sum to the first file's, and, with a baseline (a firmware that does
//! nothing), the sizes net of the baseline and their ratio to the first file's net size.
//!
//! `elf-sizes --symbols PREFIX PATH` lists instead the symbols of `PATH` whose names start with
//! `PREFIX` and their sizes (`__aeabi_d`: the double-precision soft-float helpers a Cortex-M4F
//! binary links when it computes in `f64`).

use std::process::ExitCode;

use object::{Object, ObjectSection, ObjectSymbol};

/// Sizes of the sections of one file.
#[derive(Debug, Clone, Copy)]
struct Sizes {
    text: u64,
    rodata: u64,
}

impl Sizes {
    fn sum(self) -> u64 {
        self.text + self.rodata
    }
}

fn read(path: &str) -> Result<Sizes, String> {
    let data = std::fs::read(path).map_err(|e| format!("{path}: {e}"))?;
    let file = object::File::parse(&*data).map_err(|e| format!("{path}: {e}"))?;
    let size_of = |name: &str| file.section_by_name(name).map_or(0, |s| s.size());
    Ok(Sizes {
        text: size_of(".text"),
        rodata: size_of(".rodata"),
    })
}

fn parse_arg(arg: &str) -> Result<(String, Sizes), String> {
    let (name, path) = arg
        .split_once('=')
        .ok_or_else(|| format!("expected NAME=PATH, got `{arg}`"))?;
    Ok((name.to_string(), read(path)?))
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("elf-sizes: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The symbols of `path` whose names start with `prefix`, sorted, one line each.
fn symbols(prefix: &str, path: &str) -> Result<(), String> {
    let data = std::fs::read(path).map_err(|e| format!("{path}: {e}"))?;
    let file = object::File::parse(&*data).map_err(|e| format!("{path}: {e}"))?;
    let mut found: Vec<(String, u64)> = file
        .symbols()
        .filter_map(|s| Some((s.name().ok()?.to_string(), s.size())))
        .filter(|(name, _)| name.starts_with(prefix))
        .collect();
    found.sort();
    found.dedup();
    println!("{} symbols starting with `{prefix}`", found.len());
    for (name, size) in found {
        println!("  {name} ({size} bytes)");
    }
    Ok(())
}

fn run() -> Result<(), String> {
    let mut args = std::env::args().skip(1).peekable();
    if args.peek().map(String::as_str) == Some("--symbols") {
        args.next();
        let (Some(prefix), Some(path)) = (args.next(), args.next()) else {
            return Err("usage: elf-sizes --symbols PREFIX PATH".into());
        };
        return symbols(&prefix, &path);
    }
    let mut baseline = None;
    if args.peek().map(String::as_str) == Some("--baseline") {
        args.next();
        let arg = args.next().ok_or("--baseline needs NAME=PATH")?;
        baseline = Some(parse_arg(&arg)?);
    }
    let rows = args.map(|a| parse_arg(&a)).collect::<Result<Vec<_>, _>>()?;
    let Some(&(_, first)) = rows.first() else {
        return Err("usage: elf-sizes [--baseline NAME=PATH] NAME=PATH...".into());
    };
    let net = |s: Sizes| {
        baseline
            .as_ref()
            .map(|(_, b): &(String, Sizes)| s.sum().saturating_sub(b.sum()))
    };
    let ratio = |a: u64, b: u64| {
        if b == 0 {
            f64::NAN
        } else {
            a as f64 / b as f64
        }
    };
    print!("| firmware | .text | .rodata | .text + .rodata | ratio |");
    if baseline.is_some() {
        print!(" net of baseline | net ratio |");
    }
    println!();
    print!("|---|---:|---:|---:|---:|");
    if baseline.is_some() {
        print!("---:|---:|");
    }
    println!();
    if let Some((name, b)) = &baseline {
        println!(
            "| {name} (baseline) | {} | {} | {} | | | |",
            b.text,
            b.rodata,
            b.sum()
        );
    }
    for (name, s) in &rows {
        print!(
            "| {name} | {} | {} | {} | {:.3} |",
            s.text,
            s.rodata,
            s.sum(),
            ratio(s.sum(), first.sum())
        );
        if let (Some(n), Some(n0)) = (net(*s), net(first)) {
            print!(" {n} | {:.3} |", ratio(n, n0));
        }
        println!();
    }
    Ok(())
}
