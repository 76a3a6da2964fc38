//! Pixel-space geometry: rectangles, segment clipping, polylines, dash patterns.

/// A point in pixel space (x to the right, y downwards).
pub(crate) type Px = (f64, f64);

/// An axis-aligned rectangle in pixel space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rect {
    pub left: f64,
    pub top: f64,
    pub right: f64,
    pub bottom: f64,
}

impl Rect {
    /// Whether `p` lies inside, with a tolerance of `tol` pixels.
    pub fn contains(&self, p: Px, tol: f64) -> bool {
        p.0 >= self.left - tol
            && p.0 <= self.right + tol
            && p.1 >= self.top - tol
            && p.1 <= self.bottom + tol
    }
}

/// Rounds a pixel coordinate for the backend (saturating, never panics).
pub(crate) fn ipx(p: Px) -> (i32, i32) {
    (p.0.round() as i32, p.1.round() as i32)
}

/// Clips the segment `a`–`b` to `r` (Liang–Barsky); `None` when nothing is left.
/// An endpoint inside the rectangle is returned unchanged.
pub(crate) fn clip_segment(a: Px, b: Px, r: &Rect) -> Option<(Px, Px)> {
    if !(a.0.is_finite() && a.1.is_finite() && b.0.is_finite() && b.1.is_finite()) {
        return None;
    }
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - r.left),
        (dx, r.right - a.0),
        (-dy, a.1 - r.top),
        (dy, r.bottom - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| {
        if t == 0.0 {
            a
        } else if t == 1.0 {
            b
        } else {
            (a.0 + t * dx, a.1 + t * dy)
        }
    };
    Some((at(t0), at(t1)))
}

/// Turns a sequence of optional points into the visible polylines inside `r`:
/// a missing point breaks the line, and so does leaving the rectangle.
pub(crate) fn clipped_polylines(points: &[Option<Px>], r: &Rect) -> Vec<Vec<Px>> {
    let mut lines = Vec::new();
    let mut current: Vec<Px> = Vec::new();
    for w in points.windows(2) {
        let seg = match (w[0], w[1]) {
            (Some(a), Some(b)) => clip_segment(a, b, r),
            _ => None,
        };
        match seg {
            Some((a, b)) => {
                if current.last() != Some(&a) && !current.is_empty() {
                    lines.push(std::mem::take(&mut current));
                }
                if current.is_empty() {
                    current.push(a);
                }
                current.push(b);
            }
            None => {
                if !current.is_empty() {
                    lines.push(std::mem::take(&mut current));
                }
            }
        }
    }
    if !current.is_empty() {
        lines.push(current);
    }
    lines
}

/// Cuts a polyline into dashes of length `on` separated by gaps of length `off` (pixels).
pub(crate) fn dashes(line: &[Px], on: f64, off: f64) -> Vec<Vec<Px>> {
    let mut out = Vec::new();
    if line.len() < 2 || on <= 0.0 || off < 0.0 {
        return out;
    }
    let mut drawing = true;
    let mut left = on; // length left in the current dash or gap
    let mut current = vec![line[0]];
    for w in line.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        if !len.is_finite() {
            continue;
        }
        let mut pos = 0.0;
        while len - pos > left {
            pos += left;
            let t = pos / len;
            let p = (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
            if drawing {
                current.push(p);
                out.push(std::mem::take(&mut current));
                left = off;
            } else {
                current = vec![p];
                left = on;
            }
            drawing = !drawing;
        }
        left -= len - pos;
        if drawing {
            current.push(b);
        }
    }
    if drawing && current.len() >= 2 {
        out.push(current);
    }
    out
}

/// Points along a polyline about every `step` pixels (vertices included): used to measure
/// how much of the data a legend placement would hide.
pub(crate) fn samples(line: &[Px], step: f64) -> Vec<Px> {
    let mut out: Vec<Px> = line.first().copied().into_iter().collect();
    for w in line.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        let n = if len.is_finite() {
            (len / step).ceil().clamp(1.0, 10_000.0) as usize
        } else {
            1
        };
        for i in 1..=n {
            let t = i as f64 / n as f64;
            out.push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    // Setting: pixel-space helpers on small hand-made inputs.
    // Goal: pin clipping, line breaking at gaps, and dash lengths.
    use super::*;

    const R: Rect = Rect {
        left: 0.0,
        top: 0.0,
        right: 10.0,
        bottom: 10.0,
    };

    #[test]
    fn clipping_keeps_inside_endpoints_and_cuts_outside_ones() {
        assert_eq!(
            clip_segment((5.0, 5.0), (15.0, 5.0), &R),
            Some(((5.0, 5.0), (10.0, 5.0)))
        );
        assert_eq!(clip_segment((11.0, 0.0), (20.0, 5.0), &R), None);
        assert_eq!(clip_segment((f64::NAN, 0.0), (2.0, 5.0), &R), None);
    }

    #[test]
    fn missing_points_and_excursions_break_polylines() {
        let pts = [
            Some((1.0, 1.0)),
            Some((2.0, 2.0)),
            None,
            Some((3.0, 3.0)),
            Some((4.0, 4.0)),
            Some((40.0, 4.0)),
            Some((5.0, 5.0)),
        ];
        let lines = clipped_polylines(&pts, &R);
        assert_eq!(lines.len(), 3, "{lines:?}");
        assert_eq!(lines[0], vec![(1.0, 1.0), (2.0, 2.0)]);
    }

    #[test]
    fn dashes_alternate_on_and_off_lengths() {
        let d = dashes(&[(0.0, 0.0), (20.0, 0.0)], 4.0, 2.0);
        assert_eq!(d.len(), 4);
        assert_eq!(d[0], vec![(0.0, 0.0), (4.0, 0.0)]);
        assert_eq!(d[1], vec![(6.0, 0.0), (10.0, 0.0)]);
    }
}
