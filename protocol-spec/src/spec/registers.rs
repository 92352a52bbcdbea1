//! The spec as written, `[registers]` and a command's `registers`: a device's register map (a
//! control table of named registers at addresses) and the request fields that select a run of
//! it. Part of the serde model ([`super::model`]); nothing is interpreted here.

#[cfg(feature = "schema")]
use schemars::JsonSchema;
use serde::Deserialize;
use toml::Spanned;

use super::model::{SInt, SStr};

/// `[registers]`: the device's register map.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct RegistersDef {
    /// Documentation (the device model, the source of the table).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
    /// Byte order of the registers' values (default: the protocol's).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub byte_order: Option<SStr>,
    /// The registers, each at its address.
    #[cfg_attr(feature = "schema", schemars(with = "Vec<RegisterDef>"))]
    pub map: Spanned<Vec<Spanned<RegisterDef>>>,
}

/// `{ name = "present_position", address = 132, type = "i32", unit = "pulse", access = "r" }`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct RegisterDef {
    /// Name (snake_case).
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub name: SStr,
    /// Address of the register's first byte.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub address: SInt,
    /// A primitive type (`u8`, `i16`, `u32be`, `f32`, ...): the register's size and value.
    #[serde(rename = "type")]
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub ty: SStr,
    /// Physical value = raw * scale (+ offset).
    #[cfg_attr(feature = "schema", schemars(with = "Option<f64>"))]
    pub scale: Option<Spanned<f64>>,
    /// Added after scaling.
    #[cfg_attr(feature = "schema", schemars(with = "Option<f64>"))]
    pub offset: Option<Spanned<f64>>,
    /// Unit of the (physical) value, for docs.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub unit: Option<SStr>,
    /// `"r"`, `"w"` or `"rw"` (default): who may read and write it.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub access: Option<SStr>,
    /// Documentation.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
}

/// A command's `registers = { address = "address", length = "length", answer = "params" }`:
/// fields of its request that select a run of registers, and the bytes that hold their values.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct SelectDef {
    /// The request's integer field that holds the run's first address, or, for a request
    /// answered once by each device it lists, a field of the elements of the group that lists
    /// them (`servos.address`): each device's own run.
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub address: SStr,
    /// The request's integer field that holds the number of bytes its answer carries (a field
    /// of the same group's elements when `address` is one: `servos.length`).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub length: Option<SStr>,
    /// The request's `bytes` field that holds the values it writes.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub data: Option<SStr>,
    /// The answer's `bytes` field that holds the values read.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub answer: Option<SStr>,
}
