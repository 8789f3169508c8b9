//! The slots' state at a clip's time: which attachment each shows, its colour and dark colour,
//! the draw order and the meshes' deform offsets ([`SlotPose`]). [`super::DrawList`] keeps one
//! and fills it in [`super::Character::draw_list_at`], so posing costs nothing for a character
//! drawn without its art, and drawing allocates nothing once its buffers have grown.
//!
//! Order of application (Spine's JSON export format, "Animations"): the setup state first (the
//! setup attachment, colour, dark colour and order), then the clip's attachment timelines, its
//! colour timelines, its draw order, and last the deforms of the meshes the slots then show
//! (a deform applies only while its slot shows that skin's attachment of that name).

use super::Character;
use super::art::{Attachment, Rgba};
use super::slot_clip::{SlotClip, draw_order_at};

/// Which attachment a slot shows.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
enum Shown {
    /// The setup attachment.
    #[default]
    Setup,
    /// The attachment of key `key` of attachment timeline `timeline` of the clip.
    Keyed { timeline: usize, key: usize },
}

/// The slots' state at a time (see the module's doc). Reused from frame to frame.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SlotPose {
    /// The clip whose timelines gave `shown` (`None`: the setup pose).
    clip: Option<usize>,
    shown: Vec<Shown>,
    /// Per slot, its colour.
    color: Vec<Rgba>,
    /// Per slot, its dark colour.
    dark: Vec<Option<[f64; 3]>>,
    /// The slots' indices, first drawn first.
    order: Vec<usize>,
    /// Per slot, whether `offsets[slot]` deforms the mesh it shows.
    deformed: Vec<bool>,
    /// Per slot, the deform offsets of the mesh it shows.
    offsets: Vec<Vec<f64>>,
}

impl SlotPose {
    /// The slots' indices in draw order, first drawn first.
    pub fn order(&self) -> &[usize] {
        &self.order
    }

    /// Slot `slot`'s colour. Panics if `slot` is not a slot.
    pub fn color(&self, slot: usize) -> Rgba {
        self.color[slot]
    }

    /// Slot `slot`'s dark colour, if any. Panics if `slot` is not a slot.
    pub fn dark(&self, slot: usize) -> Option<[f64; 3]> {
        self.dark[slot]
    }

    /// The deform offsets of the mesh slot `slot` shows (added to its vertex coordinates, per
    /// weight entry of a weighted mesh; coordinates past the end have none), if a deform
    /// timeline changes it. Panics if `slot` is not a slot.
    pub fn deform(&self, slot: usize) -> Option<&[f64]> {
        self.deformed[slot].then(|| self.offsets[slot].as_slice())
    }
}

impl Character {
    /// The name of the attachment slot `slot` shows in `state` (`None`: none).
    pub fn shown_attachment<'a>(&'a self, state: &SlotPose, slot: usize) -> Option<&'a str> {
        match state.shown.get(slot).copied().unwrap_or_default() {
            Shown::Setup => self.art().slots.get(slot)?.attachment.as_deref(),
            Shown::Keyed { timeline, key } => {
                let clip = self.art().clips.get(state.clip?)?;
                clip.attachments.get(timeline)?.keys.get(key)?.name.as_deref()
            }
        }
    }

    /// Slot `slot`'s attachment called `name`, looked up in skin `skin`, then in the skin
    /// called `default`, with the index of the skin it was found in.
    pub fn find_attachment(&self, slot: usize, name: &str, skin: Option<usize>) -> Option<(usize, &Attachment)> {
        let find = |k: usize| self.art().skins.get(k).and_then(|s| s.get(slot, name)).map(|a| (k, a));
        skin.and_then(find).or_else(|| self.default_skin().and_then(find))
    }

    /// Fills `state` with the slots' state of clip `clip` at its time (`(clip, seconds)`;
    /// `None`: the setup state), the attachments found as skin `skin` shows them: what
    /// [`Character::draw_list_at`] draws with, for a caller that draws by itself. A clip the
    /// character does not have gives the setup state ([`Character::draw_list_at`] refuses it).
    pub fn slot_pose(&self, clip: Option<(usize, f64)>, skin: Option<usize>, state: &mut SlotPose) {
        let slots = &self.art().slots;
        let n = slots.len();
        state.clip = clip.map(|(c, _)| c);
        state.shown.clear();
        state.shown.resize(n, Shown::Setup);
        state.color.clear();
        state.color.extend(slots.iter().map(|s| s.color));
        state.dark.clear();
        state.dark.extend(slots.iter().map(|s| s.dark));
        state.order.clear();
        state.order.extend(0..n);
        state.deformed.clear();
        state.deformed.resize(n, false);
        if state.offsets.len() < n {
            state.offsets.resize_with(n, Vec::new);
        }
        let Some((c, time)) = clip else { return };
        let Some(timelines) = self.art().clips.get(c) else { return };
        self.apply_slot_clip(timelines, time, skin, state);
    }

    /// [`Self::slot_pose`]'s clip part: `state` holds the setup state.
    fn apply_slot_clip(&self, clip: &SlotClip, time: f64, skin: Option<usize>, state: &mut SlotPose) {
        for (t, timeline) in clip.attachments.iter().enumerate() {
            let i = super::timeline::key_at(|i| timeline.keys[i].time, timeline.keys.len(), time);
            if let Some(key) = i {
                state.shown[timeline.slot] = Shown::Keyed { timeline: t, key };
            }
        }
        for timeline in &clip.colors {
            let s = timeline.slot;
            timeline.apply(time, &mut state.color[s], &mut state.dark[s]);
        }
        if let Some(order) = draw_order_at(&clip.draw_order, time) {
            state.order.clear();
            state.order.extend_from_slice(order);
        }
        for d in &clip.deforms {
            let s = d.slot;
            let shows = self
                .shown_attachment(state, s)
                .filter(|&name| name == d.attachment)
                .and_then(|name| self.find_attachment(s, name, skin));
            if let Some((k, Attachment::Mesh(_))) = shows {
                if k == d.skin && !state.deformed[s] {
                    state.deformed[s] = d.at(time, &mut state.offsets[s]);
                }
            }
        }
    }
}
