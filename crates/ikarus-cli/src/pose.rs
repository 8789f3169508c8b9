//! `ikarus pose`: a character file (Spine, DragonBones) posed as its runtime does — the setup
//! pose, an animation at a time, bones moved to targets, then the IK constraints in their order
//! — printed as every bone's world origin, rotation and tip, or drawn. The job is the edge's
//! ([`ikarus_edge::pose`], shared with `POST /api/pose`).

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use ikarus::character::Character;
use ikarus_edge::pose::{IkChoice, PhysicsAsk, PoseAsk, PoseReport, pose};

use crate::error::Error;
use crate::options::{parse_finite, parse_point};
use crate::output::{self, PendingFile};
use crate::pose_art::{ArtAsk, drawn};

/// Output format of `ikarus pose`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PoseFormat {
    /// One line per bone: name, x, y, rotation (degrees), tip x, tip y
    Text,
    /// `{"bones": [{"name", "x", "y", "rotation_deg", "tip"}, …], "unsupported": […]}`
    Json,
    /// The bones drawn (SVG), the IK targets as goals
    Svg,
    /// The bones drawn (PNG), the IK targets as goals
    Png,
}

/// Whose rules solve a character's IK constraints.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum IkRules {
    /// The runtime's: each constraint on its one or two bones, one after another in their order
    Runtime,
    /// ikarus's rig solver: every constraint at once, each a goal on its last bone's tip
    Ikarus,
}

impl IkRules {
    /// The rules the edge takes.
    #[must_use]
    pub fn rules(self) -> ikarus_edge::pose::IkRules {
        match self {
            IkRules::Runtime => ikarus_edge::pose::IkRules::Runtime,
            IkRules::Ikarus => ikarus_edge::pose::IkRules::Ikarus,
        }
    }
}

/// Whose rules solve a character's IK constraints, and an IK file: `pose`, and `animate` and
/// `track` with a character file.
#[derive(Debug, Args)]
pub struct IkArgs {
    /// With a character file: whose rules solve its IK constraints, the runtime's (one after
    /// another, in their order) or ikarus's rig solver (all at once: no constraint undoes
    /// another, limbs of any length)
    #[arg(long, value_enum, default_value_t = IkRules::Runtime)]
    pub ik: IkRules,
    /// With --ik ikarus: an IK file (TOML) adding pins, longer limbs, weights, joint limits and
    /// stiffness to the character's constraints
    #[arg(long, value_name = "FILE")]
    pub ik_file: Option<PathBuf>,
}

impl IkArgs {
    /// The rules for `character`, the IK file read and checked against it.
    pub fn choice(&self, character: &Character) -> Result<IkChoice, Error> {
        let text = match &self.ik_file {
            Some(p) => {
                let label = format!("ik file {}", p.display());
                Some((crate::input::read_text(p, &label)?, label))
            }
            None => None,
        };
        let (file, label) = match &text {
            Some((t, l)) => (Some(t.as_str()), l.as_str()),
            None => (None, "--ik-file"),
        };
        ikarus_edge::pose::rules_choice(self.ik.rules(), file, label, character)
    }

    /// `(flag, given)` for the refusals of flags that mean something only with a character.
    #[must_use]
    pub fn given(&self) -> [(&'static str, bool); 2] {
        [("--ik", self.ik != IkRules::Runtime), ("--ik-file", self.ik_file.is_some())]
    }
}

/// Pose a character file as its runtime does.
#[derive(Debug, Args)]
pub struct PoseArgs {
    /// Character file: Spine (4.0–4.2, 3.8) or DragonBones (5.x) JSON, or a Spine 4.2 binary export (.skel), told by its content
    #[arg(long, value_name = "FILE")]
    pub rig: PathBuf,
    /// Sample this animation of the file (by name) [default: the setup pose]
    #[arg(long, value_name = "NAME")]
    pub animation: Option<String>,
    /// Seconds into the animation [default: 0]
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true, value_parser = parse_finite, requires = "animation")]
    pub time: Option<f64>,
    /// Put a bone's world origin at X,Y after the animation and before the constraints (an IK
    /// target bone moves its limb), BONE=X,Y (repeatable, applied in order)
    #[arg(long, value_name = "BONE=X,Y", allow_hyphen_values = true, value_parser = parse_target)]
    pub target: Vec<(String, [f64; 2])>,
    /// The skin whose skin-required bones and constraints take part, by name [default: the skin
    /// called `default`, if the file has one]; the bones it does not turn on are not posed
    /// (`"active": false` in the JSON)
    #[arg(long, value_name = "NAME")]
    pub skin: Option<String>,
    #[command(flatten)]
    pub ik: IkArgs,
    /// Physics constraints: on plays the animation from 0 at --fps frames a second with them
    /// stepping, as a game shows it; off leaves them out (Spine's Physics.none)
    #[arg(long, value_enum, default_value_t = PhysicsSwitch::On)]
    pub physics: PhysicsSwitch,
    /// Frames a second of the play with physics
    #[arg(long, value_name = "FPS", default_value_t = 60.0, value_parser = parse_finite)]
    pub fps: f64,
    /// Output format [default: text on a terminal, json otherwise; from --out's extension for
    /// .svg and .png]
    #[arg(long, value_enum)]
    pub format: Option<PoseFormat>,
    /// Write the output to FILE instead of stdout (whole or not at all)
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    #[command(flatten)]
    pub size: crate::picture::SizeArgs,
    /// A Spine character's texture atlas (.atlas), its PNG pages beside it: the picture (.png,
    /// .svg) draws the character's art under its bones (an SVG holds the art as one embedded
    /// PNG image under the vector bones)
    #[arg(long, value_name = "FILE")]
    pub atlas: Option<PathBuf>,
    /// With --atlas: the art alone on a transparent background, the box of its vertices filling
    /// 90 % of --width × --height, centred (as Spine's own renderer fits a skeleton)
    #[arg(long)]
    pub art_only: bool,
}

/// `--physics on|off`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PhysicsSwitch {
    /// Played from 0 with the physics stepping.
    On,
    /// Left out.
    Off,
}

impl PhysicsSwitch {
    /// What a character's motion does with its physics constraints (`animate`, `track` with
    /// `--physics`; on when not given): its frames played as a game's frames, or posed each on
    /// its own.
    #[must_use]
    pub fn motion(switch: Option<Self>) -> ikarus_edge::character::motion::Physics {
        use ikarus_edge::character::motion::Physics;
        match switch {
            Some(PhysicsSwitch::Off) => Physics::Off,
            Some(PhysicsSwitch::On) | None => Physics::Played,
        }
    }
}

/// `BONE=X,Y`: the name is everything before the last `=`.
pub fn parse_target(s: &str) -> Result<(String, [f64; 2]), Error> {
    let (name, point) = s.rsplit_once('=').ok_or_else(|| Error::input(format!("expected BONE=X,Y, got {s:?}")))?;
    if name.is_empty() {
        return Err(Error::input(format!("expected BONE=X,Y with a bone's name before '=', got {s:?}")));
    }
    Ok((name.to_owned(), parse_point(point)?))
}

pub fn run(args: &PoseArgs) -> Result<(), Error> {
    let label = format!("rig file {}", args.rig.display());
    let text = crate::input::read_character_text(&args.rig, &label)?;
    if ikarus_edge::character::atlas::is_atlas(&text) {
        return Err(Error::input(format!("{label}: {}", ikarus_edge::character::atlas::ATLAS)));
    }
    if !ikarus_edge::character::is_json(&text) {
        return Err(Error::input(format!(
            "{label}: pose takes a character file (Spine or DragonBones JSON, or a Spine .skel); a rig file (TOML) is posed by solve --rig"
        )));
    }
    let loaded = ikarus_edge::character::load(&text, &label)?;
    for warning in &loaded.warnings {
        eprintln!("ikarus: {label}: {warning}");
    }
    let format = format_of(args)?;
    let art_ask = ArtAsk {
        rig: &args.rig,
        atlas: args.atlas.as_deref(),
        art_only: args.art_only,
        size: &args.size,
        svg: match format {
            PoseFormat::Svg => Some(true),
            PoseFormat::Png => Some(false),
            PoseFormat::Text | PoseFormat::Json => None,
        },
    };
    let atlas = crate::pose_art::atlas_of(&art_ask, &loaded)?;
    let file = args.out.as_deref().map(|p| PendingFile::create(p, "--out")).transpose()?;
    let ik = args.ik.choice(&loaded.character)?;
    let ask = PoseAsk {
        animation: args.animation.clone(),
        time: args.time,
        targets: args.target.clone(),
        ik,
        bends: Vec::new(),
        turns: Vec::new(),
        physics: match args.physics {
            PhysicsSwitch::On => PhysicsAsk::Play { fps: args.fps },
            PhysicsSwitch::Off => PhysicsAsk::Off,
        },
        skin: args.skin.clone(),
    };
    let bytes = match &atlas {
        Some(atlas) => crate::pose_art::draw(&art_ask, &loaded, &ask, atlas, &|| caption(args))?,
        None => {
            let report = pose(&loaded, &ask).map_err(|m| Error::input(format!("{label}: {m}")))?;
            render(&report, format, &|| caption(args), &args.size)?
        }
    };
    match file {
        Some(file) => file.commit(&bytes),
        None => output::stdout(|w: &mut dyn Write| w.write_all(&bytes)),
    }
}

/// The format asked for; else from `--out`'s extension (.svg, .png, else json); else text on
/// a terminal and json when piped.
fn format_of(args: &PoseArgs) -> Result<PoseFormat, Error> {
    if let Some(f) = args.format {
        return Ok(f);
    }
    let ext = args.out.as_deref().and_then(|p| p.extension()).and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    Ok(match ext.as_deref() {
        Some("svg") => PoseFormat::Svg,
        Some("png") => PoseFormat::Png,
        Some(_) => PoseFormat::Json,
        None => {
            crate::picture::report_format(None, false, PoseFormat::Text, PoseFormat::Json).unwrap_or(PoseFormat::Json)
        }
    })
}

/// The caption of `args`'s picture: the file, the animation and time, the targets, the solver.
fn caption(args: &PoseArgs) -> String {
    let file = args.rig.file_name().map_or_else(String::new, |f| f.to_string_lossy().into_owned());
    let mut caption = match &args.animation {
        Some(a) => format!("{file} · {a} at {} s", args.time.unwrap_or(0.0)),
        None => format!("{file} · setup pose"),
    };
    if !args.target.is_empty() {
        let n = args.target.len();
        caption.push_str(&format!(" · {n} target{}", if n == 1 { "" } else { "s" }));
    }
    if args.ik.ik == IkRules::Ikarus {
        caption.push_str(" · ikarus solver");
    }
    caption
}

/// `report` in `format`; a picture `size` large, captioned by `caption`.
pub fn render(
    report: &PoseReport,
    format: PoseFormat,
    caption: &dyn Fn() -> String,
    size: &crate::picture::SizeArgs,
) -> Result<Vec<u8>, Error> {
    Ok(match format {
        PoseFormat::Text => report.text().into_bytes(),
        PoseFormat::Json => {
            let mut v = serde_json::to_vec(report).map_err(|e| Error::runtime(format!("cannot write JSON: {e}")))?;
            v.push(b'\n');
            v
        }
        PoseFormat::Svg => ikarus_render::character_svg(&report.figure(Some(caption())), size.width, size.height)
            .map_err(drawn)?
            .into_bytes(),
        PoseFormat::Png => {
            ikarus_render::character_png(&report.figure(Some(caption())), size.width, size.height).map_err(drawn)?
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_target_is_a_name_and_a_point() {
        assert_eq!(parse_target("front-foot=1,-2.5"), Ok(("front-foot".to_owned(), [1.0, -2.5])));
        assert_eq!(parse_target("a=b=3,4"), Ok(("a=b".to_owned(), [3.0, 4.0])));
        assert!(parse_target("foot").unwrap_err().to_string().contains("BONE=X,Y"));
        assert!(parse_target("=1,2").unwrap_err().to_string().contains("bone's name"));
        assert!(parse_target("foot=1").unwrap_err().to_string().contains("two numbers"));
    }
}
