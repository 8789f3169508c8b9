//! Frames recorded during a solve, stored flat so that recording reuses its buffers.

use nalgebra::Point2;

/// Recorded frames: for each, the iteration, the joint angles and the joint positions.
///
/// Stored as flat buffers (`n` angles and `n + 1` points per frame) that a reused
/// [`Outcome`](super::Outcome) keeps between solves.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Frames {
    joints_per_frame: usize,
    iterations: Vec<u32>,
    angles: Vec<f64>,
    points: Vec<Point2<f64>>,
}

/// One recorded frame, borrowed from [`Frames`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame<'a> {
    /// The iteration the frame was taken at (0 is the start pose).
    pub iteration: u32,
    /// Joint angles, radians.
    pub angles: &'a [f64],
    /// Joint positions, base first, tip last.
    pub joints: &'a [Point2<f64>],
}

/// Frames reserved up front; more grow the buffers as usual.
const RESERVE_FRAMES: usize = 1024;

impl Frames {
    /// Clears the frames for a solve of an `n`-joint chain, reserving room for the frames it
    /// can record.
    pub(super) fn start(&mut self, n: usize, every: Option<u32>, max_iterations: u32) {
        self.joints_per_frame = n;
        self.iterations.clear();
        self.angles.clear();
        self.points.clear();
        if let Some(k) = every {
            let expected = (max_iterations / k) as usize + 2;
            let frames = expected.min(RESERVE_FRAMES);
            self.iterations.reserve(frames);
            self.angles.reserve(frames * n);
            self.points.reserve(frames * (n + 1));
        }
    }

    pub(super) fn push(&mut self, iteration: u32, angles: &[f64], joints: &[Point2<f64>]) {
        self.iterations.push(iteration);
        self.angles.extend_from_slice(angles);
        self.points.extend_from_slice(joints);
    }

    /// Records the final state; a frame already recorded at this iteration is replaced (CCD
    /// and FABRIK may end on a better pose than the one they last visited).
    pub(super) fn push_final(&mut self, iteration: u32, angles: &[f64], joints: &[Point2<f64>]) {
        if self.iterations.last() == Some(&iteration) {
            let (a, p) = (self.angles.len() - angles.len(), self.points.len() - joints.len());
            self.angles[a..].copy_from_slice(angles);
            self.points[p..].copy_from_slice(joints);
        } else {
            self.push(iteration, angles, joints);
        }
    }

    /// Number of frames.
    #[must_use]
    pub fn len(&self) -> usize {
        self.iterations.len()
    }

    /// Whether no frame was recorded.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.iterations.is_empty()
    }

    /// Frame `i`, if there is one.
    #[must_use]
    pub fn get(&self, i: usize) -> Option<Frame<'_>> {
        let n = self.joints_per_frame;
        let iteration = *self.iterations.get(i)?;
        Some(Frame {
            iteration,
            angles: &self.angles[i * n..(i + 1) * n],
            joints: &self.points[i * (n + 1)..(i + 1) * (n + 1)],
        })
    }

    /// The frames in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = Frame<'_>> + '_ {
        (0..self.len()).map(|i| self.get(i).expect("index within len"))
    }
}
