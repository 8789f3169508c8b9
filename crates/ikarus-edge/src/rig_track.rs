//! `ikarus track --rig FILE --effector NAME`: the tip of one bone follows a path, online, each
//! sample solved from the previous pose, while the rig's other goals hold and its pins stay
//! where they start (the library's [`ikarus::track::follow_rig`]); per-sample JSON (angles and
//! tips keyed by bone name), CSV or text, and a picture or GIF of the skeleton with `--out`.
//! The job and its JSON are shared with `POST /api/track` with `rig`.

use ikarus::RigTask;
use ikarus::track::{self, Path, Track, TrackMode, TrackOptions};
use serde::Serialize;

use crate::report::degrees;
use crate::rig::Rig;
use crate::rig_report::ByName;
use crate::track::TrackSummaryJson;

/// One rig track: the workflow of `ikarus track --rig` and `POST /api/track` with `rig`.
pub struct RigTrackJob<'a> {
    pub rig: &'a Rig,
    pub start: Vec<f64>,
    /// The bone whose tip follows the path.
    pub bone: usize,
    /// The goals held and the pins, without the effector.
    pub task: RigTask,
    pub path: Path,
    pub options: TrackOptions,
}

/// The index of the effector bone `name`, which must exist and have neither a goal nor a pin
/// in `task`; a problem starts with `field` and the name (`--effector hand`).
pub fn effector_index(rig: &Rig, name: &str, task: &RigTask, field: &str) -> Result<usize, String> {
    let bone = crate::rig_task::index(&rig.skeleton, name).map_err(|m| format!("{field} {name}: {m}"))?;
    if task.goals.iter().any(|g| g.bone == bone) {
        return Err(format!("{field} {name}: the bone also has a goal; the effector's goal is the path"));
    }
    if task.pins.iter().any(|p| p.bone == bone) {
        return Err(format!("{field} {name}: the bone is also pinned; a pinned tip cannot follow a path"));
    }
    Ok(bone)
}

impl RigTrackJob<'_> {
    /// Follows the path; a problem is bad input, in the library's words.
    pub fn run(&self) -> Result<Track, String> {
        let s = &self.rig.skeleton;
        track::follow_rig(s, &self.start, self.bone, &self.task, &self.path, &self.options).map_err(|e| e.to_string())
    }

    /// A one-line caption for pictures.
    pub fn caption(&self, t: &Track) -> String {
        let s = &t.summary;
        format!(
            "{} · {} follows · {} of {} reached · {} flips · largest step {:.1}°",
            self.rig.name,
            self.rig.skeleton.name(self.bone),
            s.reached,
            s.samples,
            s.flips.len(),
            s.max_step.to_degrees()
        )
    }

    /// The JSON object of a finished track.
    pub fn json<'a>(&'a self, t: &Track) -> RigTrackJson<'a> {
        let s = &self.rig.skeleton;
        let names = s.names();
        let samples = t
            .samples
            .iter()
            .map(|x| {
                let p = x.goal.target();
                let tips = crate::rig_report::tips(self.rig, &x.angles);
                RigTrackSampleJson {
                    goal: [p.x, p.y],
                    angle_deg: x.goal.orientation().map(f64::to_degrees),
                    status: x.status.as_str(),
                    error: x.error,
                    angles_deg: ByName { names, values: degrees(&x.angles) },
                    joints: ByName { names, values: tips.iter().map(|p| [p.x, p.y]).collect() },
                    step_deg: x.step.to_degrees(),
                }
            })
            .collect();
        RigTrackJson {
            rig: &self.rig.name,
            effector: s.name(self.bone),
            mode: TrackMode::Follow.name(),
            samples,
            summary: TrackSummaryJson::new(&t.summary, self.options.max_step),
        }
    }
}

/// One sample of a rig track: as an arm's, with angles and tips keyed by bone name.
#[derive(Serialize)]
pub struct RigTrackSampleJson<'a> {
    pub goal: [f64; 2],
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angle_deg: Option<f64>,
    pub status: &'static str,
    /// The largest effector error: the followed tip's, the held goals' and the pins'.
    pub error: f64,
    pub angles_deg: ByName<'a, f64>,
    pub joints: ByName<'a, [f64; 2]>,
    pub step_deg: f64,
}

/// A rig track: `ikarus track --rig --format json` and `POST /api/track` with `rig`.
#[derive(Serialize)]
pub struct RigTrackJson<'a> {
    pub rig: &'a str,
    /// The bone whose tip followed the path.
    pub effector: &'a str,
    pub mode: &'static str,
    pub samples: Vec<RigTrackSampleJson<'a>>,
    pub summary: TrackSummaryJson,
}
