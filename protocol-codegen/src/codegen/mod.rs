//! Expansion: IR to tokens.
