//! The register map of the IR (`[registers]`) and the commands that select runs of it (a
//! command's `registers`). Every name is resolved; registers are in address order and do not
//! overlap.

use super::ValueType;

/// Who may read and write a register.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// Read only (`"r"`).
    Read,
    /// Write only (`"w"`).
    Write,
    /// Read and write (`"rw"`).
    ReadWrite,
}

impl Access {
    /// The spelling of the spec (`r`, `w`, `rw`).
    pub fn as_str(self) -> &'static str {
        match self {
            Access::Read => "r",
            Access::Write => "w",
            Access::ReadWrite => "rw",
        }
    }
}

/// A named register at an address.
#[derive(Debug, Clone, PartialEq)]
pub struct Register {
    /// Name as written (snake_case).
    pub name: String,
    /// Address of its first byte.
    pub address: u32,
    /// Its bytes.
    pub size: usize,
    /// Its value: a [`ValueType::Scalar`], scaled or not.
    pub ty: ValueType,
    /// Physical unit, for docs (empty when none).
    pub unit: String,
    /// Who may read and write it.
    pub access: Access,
    /// Documentation.
    pub doc: String,
}

/// A command whose request selects a run of registers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Select {
    /// The command (index into [`Protocol::commands`](super::Protocol::commands)).
    pub command: usize,
    /// The request's struct (index into [`Protocol::structs`](super::Protocol::structs)).
    pub request: usize,
    /// The integer field that holds the first address: the request's, or with
    /// [`each`](Self::each) its group element's.
    pub address: String,
    /// The integer field that holds the number of bytes asked: the request's, or with
    /// [`each`](Self::each) its group element's.
    pub length: Option<String>,
    /// The request's `bytes` field that holds the values written.
    pub data: Option<String>,
    /// The answer's struct and its `bytes` field that holds the values read.
    pub answer: Option<(usize, String)>,
    /// For a request answered once by each id it lists, whose every listed device is asked
    /// a run of its own (`BULK_READ`): the repeated group that lists them.
    pub each: Option<PerDevice>,
}

/// The repeated group of a request whose elements each name a device and the run it is
/// asked for (`registers = { address = "servos.address", ... }` with `answers = { each =
/// "servos.id", ... }`). The answer whose sender id is an element's id carries that element's
/// run; a device listed twice is asked the run of its first element, as it answers once.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PerDevice {
    /// The request's repeated group field (`servos`).
    pub group: String,
    /// Its element struct (index into [`Protocol::structs`](super::Protocol::structs)).
    pub element: usize,
    /// The element's `u8` field that holds the device's id (`id`, from `answers.each`).
    pub id: String,
}

/// The device's register map.
#[derive(Debug, Clone, PartialEq)]
pub struct RegisterMap {
    /// Documentation.
    pub doc: String,
    /// The registers, in address order.
    pub registers: Vec<Register>,
    /// The commands that select runs of them, in command order.
    pub selects: Vec<Select>,
}

impl RegisterMap {
    /// What command `command` selects, if anything.
    pub fn select(&self, command: usize) -> Option<&Select> {
        self.selects.iter().find(|s| s.command == command)
    }
}
