//! The end-to-end tests of generated code: every bundled spec expanded with `protocol!` on its
//! golden vectors, streams, faults and random input, the integrations (tokio, async readers,
//! CAN, serde), the session machines, and random specs.
//!
//! One binary for the package's integration tests, each file here a module named as the file
//! (`cargo test -p protocol-tests --test it -- NAME::` runs one): every test binary links the
//! crates under test and their dependencies once more, and here each also expanded every spec
//! again, so one binary builds and links them once. A new file `NAME.rs` here joins with a
//! `mod NAME;` line (docs/architecture.md, "Tests").
//!
//! The no-allocation tests (`no_alloc`, and the session machines' in `session_sim`) count with
//! `allocation-counter`, whose counting allocator is the global allocator of the whole binary:
//! it counts only the allocations of the thread inside `allocation_counter::measure`, so the
//! tests running beside them on other threads neither add to their counts nor see a difference.

// `#[macro_use]`: `random_specs` calls `expand_spec!` by name, in the file `build.rs` writes.
#[macro_use]
#[path = "../support/mod.rs"]
mod support;
#[path = "../golden/mod.rs"]
mod golden;
/// The registry of bundled specs (`tests/catalogue.toml`).
#[path = "../../catalogue.rs"]
mod registry;

mod async_io;
mod bit_stream;
mod can_frames;
mod carried_codec;
mod catalogue;
mod check_vectors;
mod crsf_parser;
mod crsf_vectors;
mod derive;
mod dronecan_pydronecan;
mod dynamixel1_vectors;
mod dynamixel_vectors;
mod error_places;
mod escaped_vectors;
mod feetech_scservo;
mod handler;
mod hflink_vectors;
mod ibus_vectors;
mod inverted_bool;
mod lx16a_pylx16a;
mod mask_fields;
mod mavlink_typed;
mod mavlink_vectors;
mod msp_errors;
mod msp_vectors;
mod msp_yamspy;
mod narrow_and_seeded_checks;
mod nested_packets;
mod no_alloc;
mod number_formats;
mod packets;
mod payload_length_first;
mod payload_types;
mod peer_frames;
#[macro_use]
mod random_specs;
// After `random_specs`: it runs that module's batch, through `for_each_random_session!`.
mod random_fixtures;
mod random_sessions;
mod referee_vectors;
mod repeated_bits;
mod roborts_vectors;
mod robustness;
mod sbp_libsbp;
mod sbus_vectors;
mod scout_vectors;
mod serde_values;
mod session_client_updates;
mod session_io_async;
mod session_mavlink;
mod session_periodic;
mod session_sim;
mod shdlc_sensirion;
mod text_fields;
mod tokio_codec;
mod ubx_pyubx2;
mod ubx_vectors;
mod unterminated_text;
mod vesc_pyvesc;
mod wire_types;
