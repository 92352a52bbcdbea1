//! Nothing: the crate exists for its compile tests (`tests/ui.rs`, cases under `ui/`).
