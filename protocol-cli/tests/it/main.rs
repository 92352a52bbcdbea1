//! The `protocol` command's integration tests: every command run as a process on the bundled
//! specs and captures, live inputs (serial, CAN), exports, the report, the Wireshark dissector
//! and the C peer.
//!
//! One binary for the package's integration tests, each file here a module named as the file
//! (`cargo test -p protocol-cli --test it -- NAME::` runs one): every test binary links the
//! crates under test and their dependencies once more, so one binary builds and links them once.
//! A new file `NAME.rs` here joins with a `mod NAME;` line (docs/architecture.md, "Tests").

#[path = "../dissect/mod.rs"]
mod dissect;
#[path = "../support/mod.rs"]
mod support;

mod c_peer;
mod cli_can;
mod cli_check;
mod cli_decode;
mod cli_diagnostics;
mod cli_direction;
mod cli_dronecan;
mod cli_edges;
mod cli_encode;
mod cli_hints;
mod cli_receive_time;
mod cli_registers;
mod cli_report;
mod cli_resources;
mod cli_serial;
mod cli_session;
mod cli_session_open;
mod cli_session_refusal;
mod exports;
mod frame_counter;
mod import_mavlink;
mod report_signals;
mod tutorial;
mod twin;
mod wireshark;
mod wireshark_checks;
mod wireshark_tcp;
mod wireshark_transports;
