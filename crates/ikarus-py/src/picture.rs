//! A PNG picture's pixels, for `Rig.image` (a character's picture with its art as a NumPy
//! array): decoded by the renderer's reader of atlas pages (`ikarus_render::Page::decode_png`),
//! straight RGBA, 8 bits a channel, row 0 at the top.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

/// ``(width, height, rgba)`` of a PNG file's bytes: every colour type expanded to straight
/// RGBA8, row by row from the top; bytes that are not a PNG image raise ``ValueError`` in one
/// line naming ``label``.
#[pyfunction]
pub(crate) fn _png_rgba<'py>(py: Python<'py>, data: &[u8], label: &str) -> PyResult<(u32, u32, Bound<'py, PyBytes>)> {
    let page = ikarus_render::Page::decode_png(data, label, false).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok((page.width, page.height, PyBytes::new(py, &page.rgba)))
}
