//! Hand-made bad files and their exact messages.

use super::to_json;
