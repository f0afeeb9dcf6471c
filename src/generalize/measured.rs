//! A prototype from a measured walk: the sagittal landmarks of docs/generalize.md ("The
//! measured-walk CSV"), one row per frame, read into walk data made consistent with its own walk
//! condition. Every error names the column, the frame or the limit.
use crate::generalize::condition::BodyCondition;
use crate::generalize::error::GeneralizeError;
use crate::generalize::extract::{Condition, Sequences, assemble};
use crate::generalize::geometry::Pelvis;
use crate::generalize::parameters::GeneralizeParameters;
use crate::generalize::pose::grounded;
use crate::generalize::sequence::{Curve, Path, interpolate};
use crate::generalize::walk_data::{Phases, WalkData};

/// The markers of each side, in the columns' order.
pub const MARKERS: [&str; 6] = ["hip", "knee", "ankle", "heel", "ball", "toe"];
const HIP: usize = 0;
const KNEE: usize = 1;
const ANKLE: usize = 2;
const HEEL: usize = 3;
const BALL: usize = 4;
const TOE: usize = 5;
/// A foot comes flat when its pitch rises within this angle of its flat pitch, its heel and its
/// toes rise when they leave it by more (rad): above the round-off of the markers' angles.
const RISE: f64 = 1e-6;

/// The column names: `time_s`, then `<marker>_<side>_x_m` and `_y_m` for r and l.
pub fn columns() -> Vec<String> {
    let mut c = vec!["time_s".to_string()];
    for side in ["r", "l"] {
        for m in MARKERS {
            c.push(format!("{m}_{side}_x_m"));
            c.push(format!("{m}_{side}_y_m"));
        }
    }
    c
}

/// The frames: times and, per side (0 r, 1 l) and marker, the (x, y) of every frame.
struct Frames {
    time: Vec<f64>,
    at: [[Vec<[f64; 2]>; 6]; 2],
}

fn measured(reason: impl Into<String>) -> GeneralizeError {
    GeneralizeError::Measured(reason.into())
}

/// Parse the CSV text (`#` comment lines anywhere).
fn parse(text: &str) -> Result<Frames, GeneralizeError> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| measured(format!("the header: {e}")))?
        .iter()
        .map(str::to_string)
        .collect();
    let wanted = columns();
    if let Some(c) = header.iter().find(|c| !wanted.contains(c)) {
        return Err(measured(format!(
            "unknown column `{c}`: the columns are {}",
            wanted.join(", ")
        )));
    }
    let mut index = Vec::with_capacity(wanted.len());
    for w in &wanted {
        let found: Vec<usize> = (0..header.len()).filter(|&i| header[i] == *w).collect();
        match found.as_slice() {
            [i] => index.push(*i),
            [] => return Err(measured(format!("column `{w}` is missing"))),
            _ => return Err(measured(format!("column `{w}` is given twice"))),
        }
    }
    let mut f = Frames {
        time: Vec::new(),
        at: Default::default(),
    };
    for (row, record) in reader.records().enumerate() {
        let record = record.map_err(|e| measured(format!("frame {row}: {e}")))?;
        let mut v = Vec::with_capacity(wanted.len());
        for (k, &i) in index.iter().enumerate() {
            let cell = record.get(i).unwrap_or("");
            let x: f64 = cell.parse().map_err(|_| {
                measured(format!(
                    "frame {row}, column `{}`: `{cell}` is not a number",
                    wanted[k]
                ))
            })?;
            if !x.is_finite() {
                return Err(measured(format!(
                    "frame {row}, column `{}`: {x}: a finite number is required",
                    wanted[k]
                )));
            }
            v.push(x);
        }
        if let Some(&last) = f.time.last()
            && v[0] <= last
        {
            return Err(measured(format!(
                "frame {row}: time_s {} does not come after {last}",
                v[0]
            )));
        }
        f.time.push(v[0]);
        for side in 0..2 {
            for m in 0..6 {
                let j = 1 + 12 * side + 2 * m;
                f.at[side][m].push([v[j], v[j + 1]]);
            }
        }
    }
    Ok(f)
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// The segment lengths of both sides (thigh, shank, ah, ab, hb, bt), each the median over the
/// frames, checked frame by frame and side against side.
fn lengths(f: &Frames, p: &GeneralizeParameters) -> Result<[f64; 6], GeneralizeError> {
    const SEGMENTS: [(&str, usize, usize); 6] = [
        ("thigh (hip–knee)", HIP, KNEE),
        ("shank (knee–ankle)", KNEE, ANKLE),
        ("heel–ankle", HEEL, ANKLE),
        ("ankle–ball", ANKLE, BALL),
        ("heel–ball", HEEL, BALL),
        ("ball–toe", BALL, TOE),
    ];
    let tol = |m: f64| (p.length_tolerance * m).max(p.contact_height);
    let mut out = [0.0; 6];
    for (s, &(name, a, b)) in SEGMENTS.iter().enumerate() {
        let mut medians = [0.0; 2];
        for (side, label) in [(0, "right"), (1, "left")] {
            let v: Vec<f64> = (0..f.time.len())
                .map(|i| dist(f.at[side][a][i], f.at[side][b][i]))
                .collect();
            let m = median(&mut v.clone());
            if let Some(i) = (0..v.len()).find(|&i| (v[i] - m).abs() > tol(m)) {
                return Err(GeneralizeError::InconsistentLength {
                    segment: format!("{label} {name}"),
                    at: format!("at frame {i} (t = {} s)", f.time[i]),
                    length: v[i],
                    median: m,
                    tolerance_pct: 100.0 * p.length_tolerance,
                });
            }
            medians[side] = m;
        }
        if (medians[0] - medians[1]).abs() > tol(medians[0]) {
            return Err(GeneralizeError::InconsistentLength {
                segment: name.to_string(),
                at: "on the left side".into(),
                length: medians[1],
                median: medians[0],
                tolerance_pct: 100.0 * p.length_tolerance,
            });
        }
        out[s] = 0.5 * (medians[0] + medians[1]);
    }
    Ok(out)
}

/// The times (s) where `y` comes down to (`down`) or leaves its lowest value: where it crosses
/// the lowest value + `c`, linear between the frames.
fn contacts(time: &[f64], y: &[f64], c: f64, down: bool) -> Vec<f64> {
    let low = y.iter().copied().fold(f64::INFINITY, f64::min);
    crossings(time, y, low + c, down)
}

/// The times (s) where `y` falls (`down`) or rises through `level`, linear between the frames.
fn crossings(time: &[f64], y: &[f64], level: f64, down: bool) -> Vec<f64> {
    (1..y.len())
        .filter(|&i| {
            if down {
                y[i - 1] > level && y[i] <= level
            } else {
                y[i - 1] <= level && y[i] > level
            }
        })
        .map(|i| {
            let s = (level - y[i - 1]) / (y[i] - y[i - 1]);
            time[i - 1] + (time[i] - time[i - 1]) * s
        })
        .collect()
}

/// The toe-offs (s) of a toe tip at (`x`, `y`): where its forward speed between the frames (at
/// their midpoints, linear between them) rises through `v`, or, if it is then still within `c`
/// of its lowest height, where it next rises through that. A toe tip pivots on the floor until
/// it leaves it; one that rises in place still pivots (docs/generalize.md, "toe-off").
fn toe_offs(time: &[f64], x: &[f64], y: &[f64], c: f64, v: f64) -> Vec<f64> {
    let mid: Vec<f64> = (1..time.len())
        .map(|i| 0.5 * (time[i - 1] + time[i]))
        .collect();
    let speed: Vec<f64> = (1..time.len())
        .map(|i| (x[i] - x[i - 1]) / (time[i] - time[i - 1]))
        .collect();
    let low = y.iter().copied().fold(f64::INFINITY, f64::min);
    let rises = crossings(time, y, low + c, false);
    crossings(&mid, &speed, v, false)
        .into_iter()
        .filter_map(|t| match interpolate(time, y, t) > low + c {
            true => Some(t),
            false => rises.iter().copied().find(|&r| r >= t),
        })
        .collect()
}

/// The first step: (stance side A, t0 = A's heel strike, B's toe-off, t1 = B's heel strike,
/// A's toe-off).
fn first_step(f: &Frames, c: f64, v: f64) -> Result<(usize, [f64; 4]), GeneralizeError> {
    let ys = |side: usize, m: usize| f.at[side][m].iter().map(|p| p[1]).collect::<Vec<f64>>();
    let xs = |side: usize, m: usize| f.at[side][m].iter().map(|p| p[0]).collect::<Vec<f64>>();
    let hs = [0, 1].map(|s| contacts(&f.time, &ys(s, HEEL), c, true));
    let to = [0, 1].map(|s| toe_offs(&f.time, &xs(s, TOE), &ys(s, TOE), c, v));
    let after = |v: &[f64], t: f64| v.iter().copied().find(|&x| x > t);
    let mut best: Option<(usize, [f64; 4])> = None;
    for a in 0..2 {
        let b = 1 - a;
        for &t0 in &hs[a] {
            let step = after(&to[b], t0).and_then(|tb| {
                let t1 = after(&hs[b], tb)?;
                let ta = after(&to[a], t1)?;
                Some([t0, tb, t1, ta])
            });
            if let Some(s) = step
                && best.is_none_or(|(_, x)| s[0] < x[0])
            {
                best = Some((a, s));
            }
        }
    }
    best.ok_or_else(|| {
        measured(
            "the stride is not closed: no heel strike of one foot followed by the other's \
             toe-off, the other's heel strike and the first foot's toe-off (docs/generalize.md)",
        )
    })
}

/// A step of the clip: the stance foot A, the swing foot B and their events (s): A's heel
/// strike t0, B's toe-off, B's heel strike t1, A's toe-off; and each foot's flat pitch and toes
/// (their median on the floor: the markers' offsets).
struct Step<'a> {
    f: &'a Frames,
    a: usize,
    events: [f64; 4],
    flat: [[f64; 2]; 2],
    toeless: bool,
}

impl Step<'_> {
    fn period(&self) -> f64 {
        self.events[2] - self.events[0]
    }

    /// TOM: B's toe-off in normalized time.
    fn tom(&self) -> f64 {
        (self.events[1] - self.events[0]) / self.period()
    }

    /// The clip's time of the stance foot's normalized time: the step, then [t1, A's toe-off]
    /// onto [1, 1 + TOM].
    fn world(&self, t: f64) -> f64 {
        let [t0, _, t1, ta] = self.events;
        if t <= 1.0 {
            t0 + t * self.period()
        } else {
            t1 + (t - 1.0) / self.tom() * (ta - t1)
        }
    }

    /// The normalized time of the clip's time `w` ([`Self::world`]'s inverse).
    fn normalized(&self, w: f64) -> f64 {
        let [t0, _, t1, ta] = self.events;
        if w <= t1 {
            (w - t0) / self.period()
        } else {
            1.0 + (w - t1) / (ta - t1) * self.tom()
        }
    }

    /// Marker `m` of `side` at normalized time t (eq. 2 between the frames).
    fn at(&self, side: usize, m: usize, t: f64) -> [f64; 2] {
        let w = self.world(t);
        let col = |k: usize| {
            self.f.at[side][m]
                .iter()
                .map(|q| q[k])
                .collect::<Vec<f64>>()
        };
        [
            interpolate(&self.f.time, &col(0), w),
            interpolate(&self.f.time, &col(1), w),
        ]
    }

    /// The pitch of `side`'s foot (heel up +), less its flat pitch.
    fn pitch(&self, side: usize, t: f64) -> f64 {
        let (h, l) = (self.at(side, HEEL, t), self.at(side, BALL, t));
        (h[1] - l[1]).atan2(l[0] - h[0]) - self.flat[side][0]
    }

    /// The toes' angle from the floor (the ball up +), less its flat value; 0 without toes.
    fn meta(&self, side: usize, t: f64) -> f64 {
        if self.toeless {
            return 0.0;
        }
        let (l, o) = (self.at(side, BALL, t), self.at(side, TOE, t));
        (l[1] - o[1]).atan2(o[0] - l[0]) - self.flat[side][1]
    }

    /// The frames' normalized times strictly inside (lo, hi), with lo and hi.
    fn samples(&self, lo: f64, hi: f64) -> Vec<f64> {
        let mut t = vec![lo];
        t.extend(
            self.f
                .time
                .iter()
                .map(|&w| self.normalized(w))
                .filter(|&x| x > lo && x < hi),
        );
        if hi > lo {
            t.push(hi);
        }
        t
    }

    /// The first (or with `last` the last) time in [lo, hi] at which `g` rises through `level`,
    /// linear between the frames.
    fn rise(
        &self,
        lo: f64,
        hi: f64,
        g: &dyn Fn(f64) -> f64,
        level: f64,
        last: bool,
    ) -> Option<f64> {
        let t = self.samples(lo, hi);
        let v: Vec<f64> = t.iter().map(|&x| g(x) - level).collect();
        let mut hits = (1..t.len())
            .filter(|&i| v[i - 1] <= 0.0 && v[i] > 0.0)
            .map(|i| t[i - 1] + (t[i] - t[i - 1]) * (-v[i - 1] / (v[i] - v[i - 1])));
        if last { hits.next_back() } else { hits.next() }
    }
}

/// The flat pitch and toes of each foot: their medians over the frames with heel, ball and toe
/// on the floor (their contact levels); where there are none, at the frame where the three are
/// together least above their contact levels.
fn flat_offsets(f: &Frames, c: f64) -> [[f64; 2]; 2] {
    [0, 1].map(|side| {
        let y = |m: usize| f.at[side][m].iter().map(|q| q[1]).collect::<Vec<f64>>();
        let lowest = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
        let (h, b, t) = (y(HEEL), y(BALL), y(TOE));
        let (lh, lb, lt) = (lowest(&h) + c, lowest(&b) + c, lowest(&t) + c);
        let mut on: Vec<usize> = (0..f.time.len())
            .filter(|&i| h[i] <= lh && b[i] <= lb && t[i] <= lt)
            .collect();
        if on.is_empty() {
            // a foot that never rests on all three: the frame it comes closest
            let above = |i: usize| h[i] - lh + b[i] - lb + t[i] - lt;
            on.extend((0..f.time.len()).min_by(|&i, &j| above(i).total_cmp(&above(j))));
        }
        let angle = |p: usize, q: usize| {
            let mut v: Vec<f64> = on
                .iter()
                .map(|&i| {
                    let (u, w) = (f.at[side][p][i], f.at[side][q][i]);
                    (u[1] - w[1]).atan2(w[0] - u[0])
                })
                .collect();
            if v.is_empty() { 0.0 } else { median(&mut v) }
        };
        [angle(HEEL, BALL), angle(BALL, TOE)]
    })
}

/// The walk data of the first whole step of the measured walk in `text` (docs/generalize.md).
pub fn from_csv(text: &str, p: &GeneralizeParameters) -> Result<WalkData, GeneralizeError> {
    let f = parse(text)?;
    let c = p.contact_height;
    for side in 0..2 {
        for (m, name) in MARKERS.iter().enumerate() {
            if let Some(i) = f.at[side][m].iter().position(|q| q[1] < -c) {
                return Err(measured(format!(
                    "frame {i}: {name} ({}) is {} m below the floor (at most {c} m)",
                    ["right", "left"][side],
                    -f.at[side][m][i][1]
                )));
            }
        }
    }
    let [thigh, shin, ah, ab, hb, bt] = lengths(&f, p)?;
    let toeless = bt <= c;
    let bt = if toeless { 0.0 } else { bt };
    let body = BodyCondition::from_triangle(thigh, shin, [ah, ab, hb, bt], 0.0)?;
    let (a, events) = first_step(&f, c, p.lift_speed)?;
    let [t0, _, t1, _] = events;
    let frames = f.time.iter().filter(|&&t| t >= t0 && t <= t1).count();
    if frames < p.min_frames_per_step {
        return Err(GeneralizeError::TooFewFrames {
            frames,
            min: p.min_frames_per_step,
            t0,
            t1,
        });
    }
    let step = Step {
        f: &f,
        a,
        events,
        flat: flat_offsets(&f, c),
        toeless,
    };
    let hip = |t: f64| {
        let (r, l) = (step.at(0, HIP, t), step.at(1, HIP, t));
        [0.5 * (r[0] + l[0]), 0.5 * (r[1] + l[1])]
    };
    if hip(1.0)[0] <= hip(0.0)[0] {
        return Err(measured(
            "the pelvis does not advance over the step: x must point forward",
        ));
    }
    step_data(&step, &body, p)
}

/// The phase moments of `s`'s stance foot (the foot comes flat, its heel and its toes rise
/// through their flat values) and whether it lands flat (within `flat_angle`: FGM = 0).
fn phase_moments(s: &Step, p: &GeneralizeParameters) -> Result<(Phases, bool), GeneralizeError> {
    let a = s.a;
    let tom = s.tom();
    let end = 1.0 + tom;
    let flat_landing = -s.pitch(a, 0.0) <= p.flat_angle;
    let fgm = if flat_landing {
        0.0
    } else {
        s.rise(0.0, end, &|t| s.pitch(a, t), -RISE, false)
            .ok_or_else(|| measured("the stance foot never comes down flat"))?
    };
    let heel_off = s
        .rise(fgm, end, &|t| s.pitch(a, t), RISE, true)
        .unwrap_or(fgm);
    let lifts = s
        .samples(heel_off, end)
        .iter()
        .any(|&t| s.meta(a, t) > p.flat_angle);
    let mom = match lifts {
        true => s
            .rise(heel_off, end, &|t| s.meta(a, t), RISE, true)
            .unwrap_or(heel_off),
        false => end,
    };
    let phases = Phases {
        fgm,
        heel_off,
        mom,
        tom,
    };
    Ok((phases, flat_landing))
}

/// Where the feet of `s` stand (x of their flat ankles' N, m): the stance foot's, the swing
/// foot's after its heel strike and before its toe-off. A landing foot's heel at its lowest
/// over its heel rocker (a quarter step) + hN; the trailing foot's toe tip at t0 − (bN + bt).
fn places(s: &Step, body: &BodyCondition) -> [f64; 3] {
    let (a, b) = (s.a, 1 - s.a);
    let [t0, _, t1, _] = s.events;
    let landed = |side: usize, hs: f64| {
        let heel = &s.f.at[side][HEEL];
        let near = (0..s.f.time.len())
            .filter(|&i| s.f.time[i] >= hs && s.f.time[i] <= hs + 0.25 * s.period())
            .min_by(|&i, &j| heel[i][1].total_cmp(&heel[j][1]));
        near.map_or(s.at(side, HEEL, s.normalized(hs))[0], |i| heel[i][0]) + body.heel_to_n
    };
    let before = s.at(b, TOE, 0.0)[0] - body.ball_to_n - body.ball_to_toe;
    [landed(a, t0), landed(b, t1), before]
}

/// The sequences of eq. 4 read from `s` at its frames, x from the stance foot's N at `n_a`.
fn sequences(s: &Step, body: &BodyCondition, ph: &Phases, n_a: f64) -> Sequences {
    let (a, b) = (s.a, 1 - s.a);
    let end = 1.0 + ph.tom;
    let sampled = |lo: f64, hi: f64, g: &dyn Fn(f64) -> f64| {
        let t = s.samples(lo, hi);
        let v = t.iter().map(|&x| g(x)).collect::<Vec<f64>>();
        (t, v)
    };
    let mut t2 = s.samples(ph.fgm, ph.heel_off);
    t2.extend(s.samples(ph.heel_off, end).into_iter().skip(1));
    let f2 = t2
        .iter()
        .map(|&t| match t < ph.heel_off {
            true => 0.0,
            false => s.pitch(a, t).max(0.0),
        })
        .collect();
    let hip = |t: f64, k: usize| 0.5 * (s.at(0, HIP, t)[k] + s.at(1, HIP, t)[k]);
    // H over the stance ankle: the clip's ankle height less the one its foot's pose puts it at
    // (a foot that hovers over the floor lifts the whole clip by as much)
    let pitch = |t: f64| match (t < ph.fgm, t < ph.heel_off) {
        (true, _) => s.pitch(a, t).min(0.0),
        (false, true) => 0.0,
        _ => s.pitch(a, t).max(0.0),
    };
    let meta = |t: f64| {
        if t >= ph.mom {
            s.meta(a, t).max(0.0)
        } else {
            0.0
        }
    };
    let hover = |t: f64| s.at(a, ANKLE, t)[1] - grounded(body, 0.0, pitch(t), meta(t)).0[1];
    let (th, hx) = sampled(0.0, 1.0, &|t| hip(t, 0) - n_a);
    let (ts, f3) = sampled(ph.tom, 1.0, &|t| s.pitch(b, t));
    Sequences {
        f1: sampled(0.0, ph.fgm, &|t| s.pitch(a, t).min(0.0)),
        f2: (t2, f2),
        meta: sampled(ph.mom, end, &|t| s.meta(a, t).max(0.0)),
        f3: Curve {
            t: ts.clone(),
            v: f3,
        },
        ankle: Path {
            t: ts.clone(),
            x: sampled(ph.tom, 1.0, &|t| s.at(b, ANKLE, t)[0] - n_a).1,
            y: sampled(ph.tom, 1.0, &|t| s.at(b, ANKLE, t)[1]).1,
        },
        hip: Path {
            t: th.clone(),
            x: hx,
            y: sampled(0.0, 1.0, &|t| hip(t, 1) - hover(t)).1,
        },
        trunk: Curve {
            t: vec![0.0, 1.0],
            v: vec![0.0, 0.0],
        },
    }
}

/// The walk data of `step` on `body` ([`assemble`]d: its ends on their constraints).
fn step_data(
    s: &Step,
    body: &BodyCondition,
    p: &GeneralizeParameters,
) -> Result<WalkData, GeneralizeError> {
    let [t0, _, t1, _] = s.events;
    let (phases, flat_landing) = phase_moments(s, p)?;
    let [n_a, n_b, n_before] = places(s, body);
    let seq = sequences(s, body, &phases, n_a);
    let knee = {
        let b = 1 - s.a;
        let (h, k, an) = (s.at(b, HIP, 1.0), s.at(b, KNEE, 1.0), s.at(b, ANKLE, 1.0));
        let (u, v) = ([k[0] - h[0], k[1] - h[1]], [an[0] - k[0], an[1] - k[1]]);
        (u[0] * v[1] - u[1] * v[0])
            .abs()
            .atan2(u[0] * v[0] + u[1] * v[1])
    };
    let mut alpha = p.alphas();
    // a rigid foot keeps its toes in line, a flat landing lands flat, at any step length
    if s.toeless || phases.mom >= 1.0 + phases.tom {
        alpha[3] = 0.0;
    }
    if flat_landing {
        alpha[1] = 0.0;
    }
    let condition = Condition {
        source: format!(
            "measured walk: the step from the {} heel strike at {t0:.4} s to {t1:.4} s",
            ["right", "left"][s.a]
        ),
        body: *body,
        step_length: n_b - n_a,
        before: n_a - n_before,
        pelvis: Pelvis {
            rotation: 0.0,
            step_width: 0.0,
        },
        knee_at_strike: knee,
        lands_flat: flat_landing,
        alpha,
        phases,
    };
    assemble(condition, seq)
}
