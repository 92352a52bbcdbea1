//! What can go wrong when the codec decodes a frame ([`DecodeIssue`]) or encodes a frame
//! value ([`EncodeIssue`]).
//!
//! Decoding mirrors the runtime's [`DecodeError`] one for one (so that the codec can be
//! compared with generated code), with the names a person needs: the command, the field.
//! Encoding reports the path of the offending value (`payload.utc_time.year`).

use std::fmt;

use protocol_runtime::{DecodeError, EncodeError};

/// Why a frame that passed the engine's checks could not be decoded into a message.
#[derive(Debug, Clone, PartialEq)]
pub enum DecodeIssue {
    /// The runtime's verdict on the bytes (framing, truncation).
    Frame(DecodeError),
    /// No command has this dispatch key.
    UnknownCommand {
        /// The key's values, in dispatch order.
        id: Vec<u64>,
        /// The key as the runtime reports it: the fields concatenated, first in the high bits.
        key: u64,
    },
    /// The header matches no direction rule.
    UnknownDirection {
        /// The command.
        command: String,
    },
    /// No header field tells the spec's directions, and the decoder was given none.
    DirectionNotGiven {
        /// The spec's directions.
        directions: Vec<String>,
    },
    /// The payload's size is not the command's.
    PayloadLength {
        /// The command.
        command: String,
        /// What the runtime reports as expected.
        expected: usize,
        /// The payload's size.
        actual: usize,
    },
    /// A field holds no variant of its enum.
    InvalidEnum {
        /// The command.
        command: String,
        /// Path of the field in the payload.
        field: String,
        /// The enum.
        enum_name: String,
        /// The value on the wire (as the runtime reports it).
        value: u64,
    },
}

impl DecodeIssue {
    /// The runtime error generated code returns for the same frame.
    pub fn to_runtime(&self) -> DecodeError {
        match self {
            DecodeIssue::Frame(e) => *e,
            DecodeIssue::UnknownCommand { key, .. } => DecodeError::UnknownCommand { key: *key },
            DecodeIssue::UnknownDirection { .. } | DecodeIssue::DirectionNotGiven { .. } => {
                DecodeError::UnknownDirection
            }
            DecodeIssue::PayloadLength {
                expected, actual, ..
            } => DecodeError::PayloadLength {
                expected: *expected,
                actual: *actual,
            },
            DecodeIssue::InvalidEnum { value, .. } => DecodeError::InvalidEnum {
                value: *value,
                place: protocol_runtime::error::Place::NONE,
            },
        }
    }
}

impl fmt::Display for DecodeIssue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DecodeIssue::Frame(e) => write!(f, "{e}"),
            DecodeIssue::UnknownCommand { id, .. } => {
                let ids: Vec<String> = id.iter().map(|v| format!("{v:#x}")).collect();
                write!(f, "unknown command id {}", ids.join(", "))
            }
            DecodeIssue::UnknownDirection { command } => {
                write!(f, "{command}: the header matches no direction")
            }
            DecodeIssue::DirectionNotGiven { directions } => write!(
                f,
                "no header field tells the direction, and none was given (one of {})",
                directions.join(", ")
            ),
            DecodeIssue::PayloadLength {
                command,
                expected,
                actual,
            } => write!(
                f,
                "{command}: payload of {actual} bytes, the command's is {expected}"
            ),
            DecodeIssue::InvalidEnum {
                command,
                field,
                enum_name,
                value,
            } => write!(
                f,
                "{command}: `{field}` holds {value:#x}, which is no variant of `{enum_name}`"
            ),
        }
    }
}

impl std::error::Error for DecodeIssue {}

impl From<protocol_runtime::Reject> for DecodeIssue {
    /// A candidate the engine rejected, as generated code reports it
    /// (`DecodeError::Frame`).
    fn from(reason: protocol_runtime::Reject) -> Self {
        DecodeIssue::Frame(DecodeError::Frame(reason))
    }
}

/// Why a frame object could not be encoded. Nothing is written for it.
#[derive(Debug, Clone, PartialEq)]
pub struct EncodeIssue {
    /// path of the offending value (`payload.speed.x`, `header.sender`, `command`); empty
    /// for the object as a whole.
    pub path: String,
    /// What is wrong.
    pub message: String,
}

impl EncodeIssue {
    /// An issue at `path`.
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        EncodeIssue {
            path: path.into(),
            message: message.into(),
        }
    }

    /// A value the object must have and lacks.
    pub fn missing(path: impl Into<String>) -> Self {
        EncodeIssue::new(path, "missing")
    }

    /// The runtime refused the frame.
    pub fn runtime(e: EncodeError) -> Self {
        EncodeIssue::new("", format!("cannot encode the frame: {e}"))
    }
}

impl fmt::Display for EncodeIssue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.path.is_empty() {
            f.write_str(&self.message)
        } else {
            write!(f, "`{}`: {}", self.path, self.message)
        }
    }
}

impl std::error::Error for EncodeIssue {}
