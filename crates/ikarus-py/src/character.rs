//! A character file (Spine, DragonBones JSON) read once and posed as its runtime does, through
//! the shared pose job (`edge::pose`, the code of `ikarus pose` and `POST /api/pose`): the
//! Python `Rig` of a character holds one and turns its answers into a `Pose`.

use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::edge::{IkReq, Loaded, PhysicsAsk, PoseAsk, character_text, load_character, parse_json, pose_watched};
use crate::signals::interruptible;

/// A character file's bytes as the JSON text ``_Character`` reads: a JSON file's text as is, a
/// Spine binary export's (``.skel``) decoded, as ``--rig FILE`` reads them (``text_of``); bytes
/// that are neither raise ``ValueError`` with the CLI's line after ``label``.
#[pyfunction]
pub(crate) fn _character_text(data: &[u8], label: &str) -> PyResult<String> {
    character_text(data.to_vec(), label).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// A character file, read: ``_Character(text, label)`` raises ``ValueError`` with the CLI's
/// line (``label`` starts it, as ``rig file PATH`` does on the command line).
#[pyclass(frozen, module = "ikarus._ikarus", name = "_Character")]
pub(crate) struct PyCharacter {
    loaded: Loaded,
    label: String,
}

#[pymethods]
impl PyCharacter {
    #[new]
    fn new(text: &str, label: &str) -> PyResult<Self> {
        let loaded = load_character(text, label).map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(Self { loaded, label: label.to_owned() })
    }

    /// ``spine`` or ``dragonbones``.
    #[getter]
    fn format(&self) -> &'static str {
        self.loaded.format.as_str()
    }

    /// The version the file says it was written by.
    #[getter]
    fn version(&self) -> &str {
        &self.loaded.version
    }

    /// The bones' names, parents first, as the file lists them.
    #[getter]
    fn bones(&self) -> Vec<String> {
        self.loaded.character.bones().iter().map(|b| b.name.clone()).collect()
    }

    /// The animations' names.
    #[getter]
    fn animations(&self) -> Vec<String> {
        self.loaded.character.clips().iter().map(|c| c.name.clone()).collect()
    }

    /// What the reader left out, one line each (the CLI prints them on stderr).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.loaded.warnings.clone()
    }

    /// The pose as columns: ``name`` (list), ``x``, ``y``, ``rotation_deg``, ``tip_x``,
    /// ``tip_y`` (float64 arrays, one row per bone) and ``unsupported`` (``{"kind", "name"}``
    /// dicts), the numbers of ``ikarus pose --format json``; a refusal is ``ValueError`` with
    /// the CLI's line. ``ik``: ``"runtime"`` (default) or ``"ikarus"`` (every constraint solved
    /// together, with the IK file's text ``ik_file``); with ``"ikarus"``, ``ik`` in the answer is
    /// the JSON's ``ik`` object as text. ``ik`` is the JSON text of ``POST /api/pose``'s IK
    /// fields as one object: ``{"ik", "ik_file", "goals", "pins"}``, each optional. ``look`` is
    /// ``(skin, fps)``: the skin's name (default: the file's ``default``) and the frames a second
    /// the animation is played at from 0 with the physics constraints (``None``: physics left
    /// out).
    #[pyo3(signature = (animation=None, time=None, targets=Vec::new(), ik=None, look=(None, Some(60.0))))]
    fn pose<'py>(
        &self,
        py: Python<'py>,
        animation: Option<String>,
        time: Option<f64>,
        targets: Vec<(String, (f64, f64))>,
        ik: Option<&str>,
        look: (Option<String>, Option<f64>),
    ) -> PyResult<Bound<'py, PyDict>> {
        let (skin, fps) = look;
        let asked: IkReq = match ik {
            Some(text) => parse_json(text.as_bytes()).map_err(|e| PyValueError::new_err(e.to_string()))?,
            None => IkReq::default(),
        };
        let ik = asked.choice(&self.loaded.character).map_err(|e| PyValueError::new_err(e.to_string()))?;
        let targets = targets.into_iter().map(|(bone, (x, y))| (bone, [x, y])).collect();
        let physics = fps.map_or(PhysicsAsk::Off, |fps| PhysicsAsk::Play { fps });
        let ask = PoseAsk { animation, time, targets, ik, skin, physics, ..PoseAsk::default() };
        // Off the calling thread, watching the token Ctrl-C sets (`signals`).
        let token = ikarus::Interrupt::new();
        let report = interruptible(py, &token, || pose_watched(&self.loaded, &ask, &token))?
            .map_err(|m| PyValueError::new_err(format!("{}: {m}", self.label)))?;
        let column = |f: fn(&crate::edge::PosedBoneJson) -> f64| -> Vec<f64> { report.bones.iter().map(f).collect() };
        let out = PyDict::new(py);
        out.set_item("name", report.bones.iter().map(|b| b.name.as_str()).collect::<Vec<_>>())?;
        out.set_item("x", PyArray1::from_vec(py, column(|b| b.x)))?;
        out.set_item("y", PyArray1::from_vec(py, column(|b| b.y)))?;
        out.set_item("rotation_deg", PyArray1::from_vec(py, column(|b| b.rotation_deg)))?;
        out.set_item("tip_x", PyArray1::from_vec(py, column(|b| b.tip[0])))?;
        out.set_item("tip_y", PyArray1::from_vec(py, column(|b| b.tip[1])))?;
        let list: Vec<Bound<'py, PyDict>> = report
            .unsupported
            .iter()
            .map(|u| {
                let d = PyDict::new(py);
                d.set_item("kind", &u.kind)?;
                d.set_item("name", &u.name)?;
                Ok(d)
            })
            .collect::<PyResult<_>>()?;
        out.set_item("unsupported", list)?;
        let ik = report
            .ik
            .as_ref()
            .map(serde_json::to_string)
            .transpose()
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        out.set_item("ik", ik)?;
        Ok(out)
    }
}
