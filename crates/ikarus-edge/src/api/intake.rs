//! What an endpoint reads ([`Intake`]): from it the server knows how to take the request (its
//! method, its content type, its size cap) and where to run it (at once, or on its pool in the
//! lane the request's cost says).

/// What an endpoint reads, each kind taken one way by the server.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Intake {
    /// Nothing (`GET`): answered at once.
    Nothing,
    /// A small JSON request (`POST`, under the request cap) whose work no field can lengthen:
    /// answered at once.
    Json,
    /// A JSON request (`POST`, under the request cap) for a computation: run on the server's
    /// pool, in the lane its cost says, under the time budget.
    Computation,
    /// A file's text (`POST`, `application/toml`, under the file cap): read on the pool.
    FileText,
    /// A JSON request carrying files (`POST`, under the file cap): read on the pool.
    JsonFile,
    /// A file's text, or its bytes (`POST`, `application/toml` or `application/octet-stream`,
    /// under the file cap): read on the pool.
    FileTextOrBytes,
}

impl Intake {
    /// Whether a request brings a body (`POST`); the others ignore it (`GET`).
    #[must_use]
    pub fn takes_body(self) -> bool {
        !matches!(self, Intake::Nothing)
    }

    /// Whether its body is a file, under the file cap (`--max-file-bytes`) rather than the
    /// request cap (`--max-body-bytes`).
    #[must_use]
    pub fn takes_file(self) -> bool {
        match self {
            Intake::Nothing | Intake::Json | Intake::Computation => false,
            Intake::FileText | Intake::JsonFile | Intake::FileTextOrBytes => true,
        }
    }
}
