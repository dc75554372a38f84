//! Frame stacking: a memoryless policy fed the last `k` observations side by side, as
//! Stable-Baselines3's `VecFrameStack(n_stack=k)` gives (channels-last: the newest frame's
//! channels come last; before an episode's first observation the stack holds zeros).
//!
//! It is the benchmark's control for memory: a policy with a `k`-step window can tell
//! elapsed times `1 … k−1` apart and "k or more" from them, nothing longer.

/// The last `frames` encoded observations of each env (`[N, frames, cells, channels]`,
/// oldest frame first; envs are added as they are first encoded).
#[derive(Debug, Clone, PartialEq)]
pub struct FrameStack {
    frames: usize,
    cells: usize,
    channels: usize,
    history: Vec<f32>,
}

impl FrameStack {
    /// An empty stack of `frames` observations of `[cells, channels]`.
    pub fn new(frames: usize, cells: usize, channels: usize) -> Self {
        FrameStack {
            frames: frames.max(1),
            cells,
            channels,
            history: Vec::new(),
        }
    }

    /// Observations stacked per input.
    pub fn frames(&self) -> usize {
        self.frames
    }

    /// Floats of one observation (`cells · channels`).
    fn frame_len(&self) -> usize {
        self.cells * self.channels
    }

    /// Floats of one env's history (`frames · cells · channels`).
    fn env_len(&self) -> usize {
        self.frames * self.frame_len()
    }

    /// Every env's history, `[N, frames, cells, channels]`.
    pub fn history(&self) -> &[f32] {
        &self.history
    }

    /// Replaces every env's history (a whole number of envs; a partial one is dropped).
    pub fn set_history(&mut self, history: &[f32]) {
        let n = history.len() / self.env_len().max(1);
        self.history = history[..n * self.env_len()].to_vec();
    }

    /// Env `e`'s history, created (zeros) with those before it when first seen.
    fn env_mut(&mut self, e: usize) -> &mut [f32] {
        let len = self.env_len();
        if self.history.len() < (e + 1) * len {
            self.history.resize((e + 1) * len, 0.0);
        }
        &mut self.history[e * len..(e + 1) * len]
    }

    /// Appends `frame` (`[cells, channels]`) to env `e`'s history, dropping its oldest,
    /// and writes the stacked input `[cells, frames · channels]` to `out`.
    pub fn push(&mut self, e: usize, frame: &[f32], out: &mut [f32]) {
        let fl = self.frame_len();
        let h = self.env_mut(e);
        h.copy_within(fl.., 0);
        let last = h.len() - fl;
        h[last..].copy_from_slice(frame);
        self.write(e, out);
    }

    /// Writes the input env `e` would see if `frame` came next, without appending it.
    pub fn peek(&self, e: usize, frame: &[f32], out: &mut [f32]) {
        let fl = self.frame_len();
        let len = self.env_len();
        let mut h = vec![0.0; len];
        if let Some(old) = self.history.get(e * len..(e + 1) * len) {
            h[..len - fl].copy_from_slice(&old[fl..]);
        }
        h[len - fl..].copy_from_slice(frame);
        Self::interleave(&h, self.frames, self.cells, self.channels, out);
    }

    /// Forgets env `e`'s observations (zeros).
    pub fn reset(&mut self, e: usize) {
        let len = self.env_len();
        if let Some(h) = self.history.get_mut(e * len..(e + 1) * len) {
            h.fill(0.0);
        }
    }

    /// Forgets every env's observations.
    pub fn reset_all(&mut self) {
        self.history.fill(0.0);
    }

    /// Writes env `e`'s stacked input to `out`.
    fn write(&self, e: usize, out: &mut [f32]) {
        let len = self.env_len();
        let h = &self.history[e * len..(e + 1) * len];
        Self::interleave(h, self.frames, self.cells, self.channels, out);
    }

    /// `[frames, cells, channels]` → `[cells, frames · channels]` (per cell, the frames'
    /// channels side by side, oldest first).
    fn interleave(h: &[f32], frames: usize, cells: usize, channels: usize, out: &mut [f32]) {
        for cell in 0..cells {
            for f in 0..frames {
                let src = (f * cells + cell) * channels;
                let dst = (cell * frames + f) * channels;
                out[dst..dst + channels].copy_from_slice(&h[src..src + channels]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A frame of `cells · channels` values all equal to `v`.
    fn frame(v: f32) -> Vec<f32> {
        vec![v; 6]
    }

    #[test]
    fn the_stack_holds_the_last_k_frames_oldest_first_with_zeros_before_the_first() {
        // 3 cells × 2 channels, 3 frames: cell c of the input is [f(t-2) f(t-2) f(t-1) f(t-1) f(t) f(t)].
        let mut s = FrameStack::new(3, 3, 2);
        let mut out = vec![f32::NAN; 18];
        s.push(0, &frame(1.0), &mut out);
        assert_eq!(&out[..6], &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0]);
        s.push(0, &frame(2.0), &mut out);
        assert_eq!(&out[..6], &[0.0, 0.0, 1.0, 1.0, 2.0, 2.0]);
        s.push(0, &frame(3.0), &mut out);
        s.push(0, &frame(4.0), &mut out);
        for cell in 0..3 {
            assert_eq!(
                &out[cell * 6..cell * 6 + 6],
                &[2.0, 2.0, 3.0, 3.0, 4.0, 4.0]
            );
        }
    }

    #[test]
    fn envs_are_independent_and_a_reset_forgets_only_its_env() {
        let mut s = FrameStack::new(2, 1, 1);
        let mut out = [0.0; 2];
        s.push(1, &[5.0], &mut out);
        assert_eq!(out, [0.0, 5.0]);
        s.push(0, &[7.0], &mut out);
        assert_eq!(out, [0.0, 7.0]);
        s.push(1, &[6.0], &mut out);
        assert_eq!(out, [5.0, 6.0]);
        s.reset(1);
        s.push(1, &[8.0], &mut out);
        assert_eq!(out, [0.0, 8.0]);
        s.push(0, &[9.0], &mut out);
        assert_eq!(out, [7.0, 9.0]);
    }

    #[test]
    fn a_peek_shows_the_next_input_without_changing_the_history() {
        let mut s = FrameStack::new(2, 1, 1);
        let mut out = [0.0; 2];
        s.push(0, &[1.0], &mut out);
        s.peek(0, &[2.0], &mut out);
        assert_eq!(out, [1.0, 2.0]);
        s.push(0, &[3.0], &mut out);
        assert_eq!(out, [1.0, 3.0]);
        let saved = s.history().to_vec();
        let mut t = FrameStack::new(2, 1, 1);
        t.set_history(&saved);
        t.push(0, &[4.0], &mut out);
        assert_eq!(out, [3.0, 4.0]);
    }
}
