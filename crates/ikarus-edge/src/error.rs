//! The CLI's error: a one-line message and the exit code it maps to.

use std::fmt;

/// A failure that ends the command: bad input (exit 2) or a failure at run time (exit 1).
#[derive(Debug)]
pub enum CliError {
    /// The user's input is wrong: a flag, a file, a value. Exit code 2.
    Input(String),
    /// Something failed while running (an output that cannot be written). Exit code 1.
    Runtime(String),
}

impl CliError {
    pub fn input(msg: impl Into<String>) -> Self {
        Self::Input(msg.into())
    }

    pub fn runtime(msg: impl Into<String>) -> Self {
        Self::Runtime(msg.into())
    }

    pub fn exit_code(&self) -> i32 {
        match self {
            Self::Input(_) => 2,
            Self::Runtime(_) => 1,
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Input(m) | Self::Runtime(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for CliError {}
