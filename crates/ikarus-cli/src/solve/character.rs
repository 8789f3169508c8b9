//! `ikarus solve --rig CHARACTER.json`: goals on a character's bones' tips (and pins), solved
//! together with its IK constraints by ikarus's solver from its setup pose
//! ([`ikarus_edge::pose::add_goals`]); the answer is `ikarus pose`'s, with each goal's miss.

use ikarus_edge::pose::{IkChoice, PoseAsk, add_goals, pose};

use super::{Format, SolveArgs};
use crate::character_motion::{CharacterFile, refuse_foreign};
use crate::error::Error;
use crate::goal_args::{GoalArg, Target};
use crate::output;
use crate::picture::{PictureFormat, report_format};
use crate::pose::{IkArgs, IkRules, PoseFormat, render};

pub(super) fn run(args: &SolveArgs, file: &CharacterFile) -> Result<(), Error> {
    let mut foreign = vec![
        ("--goal-angle", args.goal_angle.is_some()),
        ("--batch", args.batch.is_some()),
        ("--threads", args.threads.is_some()),
        ("--summary-json", args.summary_json.is_some()),
        ("--record-every", args.record_every.is_some()),
        ("--mix", args.body.rig_task.mix.is_some()),
    ];
    foreign.extend(args.body.solver.given());
    refuse_foreign(&foreign)?;
    if args.format == Some(Format::Csv) {
        return Err(Error::input("--format csv: a character's solve is written as json or text"));
    }
    let c = &file.loaded.character;
    let targets = args
        .goal
        .iter()
        .map(|g| match g {
            GoalArg::Named { bone, x, y, angle_deg } => {
                Ok(Target { bone: bone.clone(), x: *x, y: *y, angle_deg: *angle_deg, source: g.text() })
            }
            GoalArg::Point(_) => {
                Err(Error::input(format!("{}: a character's goal names its bone: --goal BONE=X,Y[,DEG]", g.text())))
            }
        })
        .collect::<Result<Vec<_>, _>>()?;
    let task = &args.body.rig_task;
    let goals = task.named(&targets)?;
    let mut counts = vec![None; targets.len()];
    for (name, n) in &args.bones {
        let i = targets.iter().position(|t| t.bone == *name).ok_or_else(|| {
            Error::input(format!("--bones {name}={n}: no goal on bone {name:?} (give it a --goal NAME=X,Y)"))
        })?;
        if counts[i].replace(*n).is_some() {
            return Err(Error::input(format!("--bones {name}={n}: --bones given twice for bone {name:?}")));
        }
    }
    let IkChoice::Ikarus(mut rules) = (IkArgs { ik: IkRules::Ikarus, ik_file: args.ik_file.clone() }).choice(c)? else {
        unreachable!("ikarus's rules asked for")
    };
    let field = |f| task.field(&targets, f);
    add_goals(&mut rules, c, &goals, &counts, &task.pin, &field)
        .map_err(|m| Error::input(format!("{}: {m}", file.label)))?;
    let picture = args.picture.prepare()?;
    let ask = PoseAsk { ik: IkChoice::Ikarus(rules), ..PoseAsk::default() };
    let report = pose(&file.loaded, &ask).map_err(|m| Error::input(format!("{}: {m}", file.label)))?;
    let caption = || {
        let name = args.body.rig.as_deref().and_then(|p| p.file_name()).map(|f| f.to_string_lossy().into_owned());
        let n = targets.len();
        format!(
            "{} · {n} goal{} · ikarus solver{}",
            name.unwrap_or_default(),
            if n == 1 { "" } else { "s" },
            report.ik.as_ref().and_then(|k| k.status.as_ref()).map(|s| format!(" · {s}")).unwrap_or_default()
        )
    };
    if let Some(format) = report_format(args.format, picture.is_some(), Format::Text, Format::Json) {
        let format = if format == Format::Json { PoseFormat::Json } else { PoseFormat::Text };
        let bytes = render(&report, format, &caption, &args.picture.size)?;
        output::stdout(|w| w.write_all(&bytes))?;
    }
    if let Some(out) = picture {
        let format = if out.format == PictureFormat::Png { PoseFormat::Png } else { PoseFormat::Svg };
        out.commit(&render(&report, format, &caption, &args.picture.size)?)?;
    }
    Ok(())
}
