//! A rig for `hcm diagnose` that shares no code path with hcm's simulator: a sphere
//! (radius R, mass m) dropped along z onto a rigid plane under gravity, its contact laws
//! written here from the paper's formulas (not `hcm_core::law`/`effect`), integrated by
//! classic fixed-step RK4 (not the adaptive Dormand–Prince of `hcm_host::simulate`), and
//! recorded as a rig records it: a force sensor at its own rate with noise and, if asked,
//! lag, offset and a ringing mount; the motion at the force rows or at a camera's frames.
//!
//! Conventions as hcm's: δ = R − pz > 0 in contact, δ̇ = −vz > 0 approaching, the force
//! on the ball along +z. Flight is the closed form of free fall; only the contact is
//! integrated, from the exact touch-down to the δ = 0 crossing found on the step's cubic.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::fmt::Write;

/// The base contact law (paper Eq 2–5; Hunt–Crossley as hcm's README writes it).
#[derive(Clone, Copy, Debug)]
pub enum Base {
    /// f = k·δ^n, Eq 2.
    Hertz,
    /// f = k·δ^n·(1 + 3(1 − e²)/4·δ̇/δ̇0), Eq 4–5, restitution e (–).
    LankaraniNikravesh(f64),
    /// f = k·δ^n·(1 + χ·δ̇), damping factor χ (s/m).
    HuntCrossley(f64),
}

/// A physical effect hidden in the contact, as hcm's catalogue defines it.
#[derive(Clone, Copy, Debug)]
pub enum Physical {
    /// f += c·δ̇, c (N·s/m).
    Viscous(f64),
    /// f += c·δ^p·δ̇: (c (N·s/m^(1+p)), p (–)).
    Hysteresis(f64, f64),
    /// f += f_el·((δ/δ_ref)^Δ − 1): (Δ (–), δ_ref (m)).
    StiffnessExponent(f64, f64),
    /// f −= a in contact, a (N).
    Adhesion(f64),
    /// Unloading below δ_max at δ_eff = (δ − ρ·δ_max)/(1 − ρ), ρ (–).
    Plasticity(f64),
    /// Out of the catalogue's shape: a plastic set ρ (–) unloading along another curve,
    /// f = k·δ_max^n·((δ − ρ·δ_max)/((1 − ρ)·δ_max))^m, m (–) ≠ n.
    PlasticCurve(f64, f64),
    /// Out of the catalogue's shape: damping nonlinear in the rate,
    /// f += c·δ^p·sign(δ̇)·|δ̇|^q: (c (N·s^q/m^(p+q)), p (–), q (–)), q ≠ 1.
    RateDamping(f64, f64, f64),
}

/// A decaying ringing of the sensor mount, A·e^(−t'/T)·sin(2π·f_r·t') after touch-down.
#[derive(Clone, Copy, Debug)]
pub struct Resonance {
    /// Amplitude A (N).
    pub amplitude: f64,
    /// Decay time T (s).
    pub decay: f64,
    /// Frequency f_r (Hz).
    pub frequency: f64,
}

/// The force sensor.
#[derive(Clone, Copy, Debug)]
pub struct Sensor {
    /// Sampling rate (Hz).
    pub rate: f64,
    /// σ_f of its white Gaussian noise (N).
    pub noise: f64,
    /// Lag τ (s): it reads f(t − τ).
    pub delay: f64,
    /// Offset b (N), in flight too.
    pub offset: f64,
    /// Gain g (–): it reads g·f(t − τ) + b.
    pub gain: f64,
    /// Quadratic nonlinearity κ (1/N): it reads g·(f + κ·f²)(t − τ) + b.
    pub nonlinearity: f64,
    /// Time constant T of a first-order low-pass filter on the force (s), 0 for none:
    /// it reads g·y(t − τ) + b with T·ẏ + y = f + κ·f².
    pub filter: f64,
    /// Ringing of the mount, if any.
    pub resonance: Option<Resonance>,
}

/// How the motion (pz, vz) is recorded.
#[derive(Clone, Copy, Debug)]
pub enum Motion {
    /// At every force row, from the fine trajectory plus white noise: (σ_z (m), σ_v (m/s)).
    AtForceRows(f64, f64),
    /// A camera at `frame_rate` (Hz) with position noise σ_z (m), cubic-splined through
    /// its frames onto the force rows (vz the spline's slope): full rows, readable today.
    CameraSplined {
        /// The camera's frame rate (Hz).
        frame_rate: f64,
        /// σ_z of the white Gaussian noise on each frame's position (m).
        position_noise: f64,
    },
    /// A camera's frames as rows of their own, force cells empty, and force rows with
    /// empty motion cells; vz at the frames with noise σ_v (m/s), or empty if None.
    Camera {
        /// The camera's frame rate (Hz).
        frame_rate: f64,
        /// σ_z of the white Gaussian noise on each frame's position (m).
        position_noise: f64,
        /// σ_v of the white Gaussian noise on each frame's vz (m/s); None: vz empty.
        velocity_noise: Option<f64>,
    },
}

/// The whole rig: ball, ground, drop, hidden physics and recording.
#[derive(Clone, Debug)]
pub struct Rig {
    /// Ball radius R (m).
    pub radius: f64,
    /// Ball mass m (kg).
    pub mass: f64,
    /// Effective modulus E* of ball and ground (Pa), [`effective_modulus`].
    pub effective_modulus: f64,
    /// Elastic exponent n (–).
    pub exponent: f64,
    /// The base law.
    pub base: Base,
    /// Mean impact speed (m/s).
    pub impact_speed: f64,
    /// Run-to-run scatter of the impact speed, relative σ (–).
    pub speed_scatter: f64,
    /// Gravity g (m/s², downwards).
    pub gravity: f64,
    /// Hidden physical effects.
    pub effects: Vec<Physical>,
    /// The force sensor.
    pub sensor: Sensor,
    /// The motion channels.
    pub motion: Motion,
    /// Recorded before touch-down and after lift-off (s).
    pub margin: f64,
    /// RK4 step through the contact (s).
    pub step: f64,
}

/// The truth of one run, for assertions.
#[derive(Clone, Debug, PartialEq)]
pub struct RunTruth {
    /// Run identifier as written.
    pub id: String,
    /// Touch-down time, at δ = 0 (s).
    pub touch_down: f64,
    /// Lift-off time, at δ = 0 (s).
    pub lift_off: f64,
    /// Impact speed δ̇0 (m/s).
    pub impact_speed: f64,
    /// Separation speed −δ̇ at lift-off (m/s).
    pub separation_speed: f64,
    /// Deepest indentation δ_max (m).
    pub max_depth: f64,
    /// Largest contact force (N), before the sensor.
    pub peak_force: f64,
}

/// A recording: the CSV text in the measured-data format and the truth of each run.
#[derive(Clone, Debug)]
pub struct Recording {
    /// The measured data, as a CSV file holds them.
    pub csv: String,
    /// The truth of each run, in the CSV's run order.
    pub runs: Vec<RunTruth>,
}

/// E* = E1·E2/(E1·(1 − ν2²) + E2·(1 − ν1²)) (Pa) of two materials (E (Pa), ν (–)), Eq 3.
pub fn effective_modulus((e1, nu1): (f64, f64), (e2, nu2): (f64, f64)) -> f64 {
    e1 * e2 / (e1 * (1.0 - nu2 * nu2) + e2 * (1.0 - nu1 * nu1))
}

/// A standard normal draw (Box–Muller).
fn gaussian(rng: &mut ChaCha8Rng) -> f64 {
    let u1 = 1.0 - rng.random::<f64>();
    let u2 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

impl Rig {
    /// A steel ball of radius R (m) on a ground of (E (Pa), ν (–)), Lankarani–Nikravesh
    /// with restitution 0.9, at 1.4 m/s, force at 1 MHz with σ_f = 15 N, exact motion.
    pub fn steel_ball(radius: f64, ground: (f64, f64)) -> Rig {
        let mass = 7800.0 * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3);
        Rig {
            radius,
            mass,
            effective_modulus: effective_modulus((2.06e11, 0.3), ground),
            exponent: 1.5,
            base: Base::LankaraniNikravesh(0.9),
            impact_speed: 1.4,
            speed_scatter: 0.0,
            gravity: 9.81,
            effects: Vec::new(),
            sensor: Sensor {
                rate: 1e6,
                noise: 15.0,
                delay: 0.0,
                offset: 0.0,
                gain: 1.0,
                nonlinearity: 0.0,
                filter: 0.0,
                resonance: None,
            },
            motion: Motion::AtForceRows(0.0, 0.0),
            margin: 100e-6,
            step: 2e-9,
        }
    }

    /// Hertz stiffness k = 4/3·E*·√R (N/m^1.5) of a sphere on a plane, Eq 3.
    pub fn stiffness(&self) -> f64 {
        4.0 / 3.0 * self.effective_modulus * self.radius.sqrt()
    }

    /// The contact force (N) at δ (m), δ̇ (m/s), impact speed δ̇0 and deepest δ_max so far.
    pub fn force(&self, depth: f64, rate: f64, approach: f64, max_depth: f64) -> f64 {
        let mut d = depth;
        let unloading = depth > 0.0 && rate < 0.0 && depth < max_depth;
        for e in &self.effects {
            match *e {
                Physical::Plasticity(rho) if unloading => {
                    d = (depth - rho * max_depth) / (1.0 - rho);
                }
                Physical::PlasticCurve(rho, m) if unloading => {
                    let s = (depth - rho * max_depth) / ((1.0 - rho) * max_depth);
                    d = if s > 0.0 {
                        max_depth * s.powf(m / self.exponent)
                    } else {
                        0.0
                    };
                }
                _ => {}
            }
        }
        if d <= 0.0 {
            return 0.0;
        }
        let elastic = self.stiffness() * d.powf(self.exponent);
        let mut f = match self.base {
            Base::Hertz => elastic,
            Base::LankaraniNikravesh(e) => elastic * (1.0 + 0.75 * (1.0 - e * e) * rate / approach),
            Base::HuntCrossley(chi) => elastic * (1.0 + chi * rate),
        };
        for e in &self.effects {
            f += match *e {
                Physical::Viscous(c) => c * rate,
                Physical::Hysteresis(c, p) => c * d.powf(p) * rate,
                Physical::StiffnessExponent(change, reference) => {
                    elastic * ((d / reference).powf(change) - 1.0)
                }
                Physical::Adhesion(a) => -a,
                Physical::Plasticity(_) | Physical::PlasticCurve(..) => 0.0,
                Physical::RateDamping(c, p, q) => {
                    c * d.powf(p) * rate.signum() * rate.abs().powf(q)
                }
            };
        }
        f
    }

    /// δ̈ = g − f/m (m/s²).
    fn acceleration(&self, depth: f64, rate: f64, approach: f64, max_depth: f64) -> f64 {
        self.gravity - self.force(depth, rate, approach, max_depth) / self.mass
    }

    /// The contact of one impact at `approach` (m/s), from touch-down at t = 0.
    pub fn impact(&self, approach: f64) -> Contact {
        let h = self.step;
        let (mut x, mut v, mut deepest) = (0.0_f64, approach, 0.0_f64);
        let mut c = Contact {
            step: h,
            depth: vec![x],
            rate: vec![v],
            accel: vec![self.gravity],
            force: vec![0.0],
            lift_off: f64::NAN,
            separation_speed: f64::NAN,
        };
        let a = |x: f64, v: f64, m: f64| self.acceleration(x, v, approach, m);
        while x > 0.0 || c.depth.len() == 1 {
            assert!(c.depth.len() < 100_000_000, "the contact does not end");
            let m = |y: f64| deepest.max(y);
            let (k1x, k1v) = (v, a(x, v, m(x)));
            let (x2, v2) = (x + 0.5 * h * k1x, v + 0.5 * h * k1v);
            let (k2x, k2v) = (v2, a(x2, v2, m(x2)));
            let (x3, v3) = (x + 0.5 * h * k2x, v + 0.5 * h * k2v);
            let (k3x, k3v) = (v3, a(x3, v3, m(x3)));
            let (x4, v4) = (x + h * k3x, v + h * k3v);
            let (k4x, k4v) = (v4, a(x4, v4, m(x4)));
            x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
            v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
            deepest = deepest.max(x);
            let f = self.force(x, v, approach, deepest);
            c.depth.push(x);
            c.rate.push(v);
            c.accel.push(self.gravity - f / self.mass);
            c.force.push(f);
        }
        // The δ = 0 crossing on the last step's cubic, by bisection.
        let last = c.depth.len() - 2;
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if c.cubic(last, mid).0 > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        c.lift_off = (last as f64 + lo) * h;
        c.separation_speed = -c.cubic(last, lo).1;
        c
    }

    /// The sensor element's output f + κ·f² at the contact's nodes, through the
    /// first-order filter if any: exact for an input linear between the nodes,
    /// y₊ = f₊ − m·T + (y − f + m·T)·e^(−h/T), m the input's slope (N/s).
    fn filtered(&self, contact: &Contact) -> Vec<f64> {
        let kappa = self.sensor.nonlinearity;
        let input: Vec<f64> = contact.force.iter().map(|f| f + kappa * f * f).collect();
        let tau = self.sensor.filter;
        if tau <= 0.0 {
            return input;
        }
        let (h, decay) = (contact.step, (-contact.step / tau).exp());
        let mut y = vec![input[0]];
        for k in 1..input.len() {
            let slope = (input[k] - input[k - 1]) / h;
            let previous = y[k - 1];
            y.push(input[k] - slope * tau + (previous - input[k - 1] + slope * tau) * decay);
        }
        y
    }

    /// Writes `runs` runs, deterministic for `seed`.
    pub fn record(&self, runs: usize, seed: u64) -> Recording {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut csv = String::from(
            "run,body,time,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,fx,fy,fz,tx,ty,tz\n",
        );
        let mut truths = Vec::new();
        for r in 0..runs {
            let speed = self.impact_speed * (1.0 + self.speed_scatter * gaussian(&mut rng));
            let dt = 1.0 / self.sensor.rate;
            let touch_down = self.margin + dt * rng.random::<f64>();
            let contact = self.impact(speed);
            let fly = Flight {
                rig: self,
                touch_down,
                speed,
                filtered: self.filtered(&contact),
                contact: &contact,
            };
            let end = touch_down + contact.lift_off + self.margin;
            let forces: Vec<(f64, f64)> = (0..)
                .map(|k| k as f64 * dt)
                .take_while(|&t| t <= end)
                .map(|t| (t, self.read_force(&fly, t, &mut rng)))
                .collect();
            let id = r.to_string();
            self.write_rows(&mut csv, &id, &fly, &forces, end, &mut rng);
            truths.push(RunTruth {
                id,
                touch_down,
                lift_off: touch_down + contact.lift_off,
                impact_speed: speed,
                separation_speed: contact.separation_speed,
                max_depth: contact.depth.iter().copied().fold(0.0, f64::max),
                peak_force: contact.force.iter().copied().fold(0.0, f64::max),
            });
        }
        Recording { csv, runs: truths }
    }

    /// What the sensor records at `t` (s): g·f(t − τ) + b + ringing + noise (N).
    fn read_force(&self, fly: &Flight, t: f64, rng: &mut ChaCha8Rng) -> f64 {
        let s = &self.sensor;
        let read = fly.read(t - s.delay);
        let mut f = s.gain * read + s.offset + s.noise * gaussian(rng);
        if let Some(ring) = s.resonance.filter(|_| t >= fly.touch_down) {
            let since = t - fly.touch_down;
            f += ring.amplitude
                * (-since / ring.decay).exp()
                * (std::f64::consts::TAU * ring.frequency * since).sin();
        }
        f
    }

    /// Appends the rows of one run: force rows at `forces`, motion as `self.motion` says.
    fn write_rows(
        &self,
        csv: &mut String,
        id: &str,
        fly: &Flight,
        forces: &[(f64, f64)],
        end: f64,
        rng: &mut ChaCha8Rng,
    ) {
        let full = |csv: &mut String, t: f64, z: f64, v: f64, f: f64| {
            writeln!(
                csv,
                "{id},ball,{t},0,0,{z},1,0,0,0,0,0,{v},0,0,0,0,0,{f},0,0,0"
            )
            .unwrap()
        };
        match self.motion {
            Motion::AtForceRows(sz, sv) => {
                for &(t, f) in forces {
                    let (z, v) = fly.motion(t);
                    let (z, v) = (z + sz * gaussian(rng), v + sv * gaussian(rng));
                    full(csv, t, z, v, f);
                }
            }
            Motion::CameraSplined {
                frame_rate,
                position_noise,
            } => {
                let frames = self.frames(fly, frame_rate, position_noise, None, end, rng);
                let spline = Spline::natural(&frames);
                for &(t, f) in forces {
                    let (z, v) = spline.at(t);
                    full(csv, t, z, v, f);
                }
            }
            Motion::Camera {
                frame_rate,
                position_noise,
                velocity_noise,
            } => {
                let frames = self.frames(fly, frame_rate, position_noise, velocity_noise, end, rng);
                let (mut i, mut j) = (0, 0);
                while i < forces.len() || j < frames.len() {
                    let tf = forces.get(i).map_or(f64::INFINITY, |x| x.0);
                    let tc = frames.get(j).map_or(f64::INFINITY, |x| x.0);
                    let motion = if tc <= tf {
                        let (_, z, v) = frames[j];
                        j += 1;
                        // A channel is filled whole or left empty whole: without a
                        // measured velocity all of vx, vy, vz are empty; a camera does
                        // not measure the angular velocity.
                        let v = v.map_or(",,".to_owned(), |v| format!("0,0,{v}"));
                        format!("0,0,{z},1,0,0,0,{v},,,")
                    } else {
                        ",,,,,,,,,,,,".to_owned()
                    };
                    let force = if tf <= tc {
                        i += 1;
                        format!("0,0,{},0,0,0", forces[i - 1].1)
                    } else {
                        ",,,,,".to_owned()
                    };
                    writeln!(csv, "{id},ball,{},{motion},{force}", tf.min(tc)).unwrap();
                }
            }
        }
    }

    /// Camera frames (t (s), pz (m), vz (m/s) if measured) over [0, end], the first at a
    /// random phase of the frame period.
    fn frames(
        &self,
        fly: &Flight,
        frame_rate: f64,
        position_noise: f64,
        velocity_noise: Option<f64>,
        end: f64,
        rng: &mut ChaCha8Rng,
    ) -> Vec<(f64, f64, Option<f64>)> {
        let phase = rng.random::<f64>() / frame_rate;
        (0..)
            .map(|k| phase + k as f64 / frame_rate)
            .take_while(|&t| t <= end)
            .map(|t| {
                let (z, v) = fly.motion(t);
                let z = z + position_noise * gaussian(rng);
                (t, z, velocity_noise.map(|s| v + s * gaussian(rng)))
            })
            .collect()
    }
}

/// The integrated contact: RK4 nodes at `step` from touch-down (t = 0).
#[derive(Clone, Debug)]
pub struct Contact {
    /// Node spacing (s).
    pub step: f64,
    /// Indentation δ (m) at the nodes.
    pub depth: Vec<f64>,
    /// Indentation rate δ̇ (m/s) at the nodes.
    pub rate: Vec<f64>,
    /// Indentation acceleration δ̈ (m/s²) at the nodes.
    pub accel: Vec<f64>,
    /// Contact force f (N) at the nodes.
    pub force: Vec<f64>,
    /// Lift-off time after touch-down (s).
    pub lift_off: f64,
    /// Separation speed −δ̇ at lift-off (m/s).
    pub separation_speed: f64,
}

impl Contact {
    /// (δ, δ̇) at fraction s ∈ [0, 1] of step i: cubic Hermite of δ with slopes δ̇, and of
    /// δ̇ with slopes δ̈ (both fourth-order accurate, like the RK4 nodes).
    fn cubic(&self, i: usize, s: f64) -> (f64, f64) {
        let h = self.step;
        let hermite = |y0: f64, y1: f64, d0: f64, d1: f64| {
            let (s2, s3) = (s * s, s * s * s);
            (2.0 * s3 - 3.0 * s2 + 1.0) * y0
                + (s3 - 2.0 * s2 + s) * h * d0
                + (-2.0 * s3 + 3.0 * s2) * y1
                + (s3 - s2) * h * d1
        };
        let (x, v, a) = (&self.depth, &self.rate, &self.accel);
        (
            hermite(x[i], x[i + 1], v[i], v[i + 1]),
            hermite(v[i], v[i + 1], a[i], a[i + 1]),
        )
    }
}

/// One run's whole trajectory: free fall, the integrated contact, free flight.
struct Flight<'a> {
    rig: &'a Rig,
    /// Touch-down time (s) in the run's clock.
    touch_down: f64,
    /// Impact speed (m/s).
    speed: f64,
    contact: &'a Contact,
    /// The sensor element's output at the contact's nodes ([`Rig::filtered`]) (N).
    filtered: Vec<f64>,
}

impl Flight<'_> {
    /// Where `t` (s) falls in the contact: (step index, fraction), or None outside it.
    fn locate(&self, t: f64) -> Option<(usize, f64)> {
        let since = t - self.touch_down;
        if since < 0.0 || since >= self.contact.lift_off {
            return None;
        }
        let x = since / self.contact.step;
        let i = (x.floor() as usize).min(self.contact.depth.len() - 2);
        Some((i, x - i as f64))
    }

    /// (pz (m), vz (m/s)) at `t` (s).
    fn motion(&self, t: f64) -> (f64, f64) {
        let (r, g, c) = (self.rig.radius, self.rig.gravity, self.contact);
        let (depth, rate) = match self.locate(t) {
            Some((i, s)) => c.cubic(i, s),
            None if t < self.touch_down => {
                let s = t - self.touch_down;
                (self.speed * s + 0.5 * g * s * s, self.speed + g * s)
            }
            None => {
                let s = t - self.touch_down - c.lift_off;
                (
                    -c.separation_speed * s + 0.5 * g * s * s,
                    -c.separation_speed + g * s,
                )
            }
        };
        (r - depth, -rate)
    }

    /// What the sensor element outputs at `t` (s), before gain, offset and noise (N):
    /// [`Rig::filtered`] linear between the nodes, 0 before touch-down and, after
    /// lift-off, the filter's last output decaying with its time constant.
    fn read(&self, t: f64) -> f64 {
        let y = &self.filtered;
        match self.locate(t) {
            Some((i, s)) => y[i] + s * (y[i + 1] - y[i]),
            None if t < self.touch_down => 0.0,
            None => {
                let tau = self.rig.sensor.filter;
                let since = t - self.touch_down - self.contact.lift_off;
                let last = y[y.len() - 1];
                if tau > 0.0 {
                    last * (-since / tau).exp()
                } else {
                    0.0
                }
            }
        }
    }
}

/// A natural cubic spline through camera frames (t, pz), for splined motion.
struct Spline {
    t: Vec<f64>,
    z: Vec<f64>,
    /// Second derivatives at the knots (m/s²).
    m: Vec<f64>,
}

impl Spline {
    /// The natural spline (zero curvature at both ends) through `frames`.
    fn natural(frames: &[(f64, f64, Option<f64>)]) -> Spline {
        let t: Vec<f64> = frames.iter().map(|f| f.0).collect();
        let z: Vec<f64> = frames.iter().map(|f| f.1).collect();
        let n = t.len();
        let mut m = vec![0.0; n];
        // Thomas algorithm on the tridiagonal system of the interior knots.
        let (mut c, mut d) = (vec![0.0; n], vec![0.0; n]);
        for i in 1..n - 1 {
            let (h0, h1) = (t[i] - t[i - 1], t[i + 1] - t[i]);
            let rhs = 6.0 * ((z[i + 1] - z[i]) / h1 - (z[i] - z[i - 1]) / h0);
            let diag = 2.0 * (h0 + h1) - h0 * c[i - 1];
            c[i] = h1 / diag;
            d[i] = (rhs - h0 * d[i - 1]) / diag;
        }
        for i in (1..n - 1).rev() {
            m[i] = d[i] - c[i] * m[i + 1];
        }
        Spline { t, z, m }
    }

    /// (pz (m), vz (m/s)) at `time` (s), extrapolating linearly beyond the end knots.
    fn at(&self, time: f64) -> (f64, f64) {
        let (t, z, m) = (&self.t, &self.z, &self.m);
        let i = t.partition_point(|&x| x <= time).clamp(1, t.len() - 1) - 1;
        let h = t[i + 1] - t[i];
        let (a, b) = ((t[i + 1] - time) / h, (time - t[i]) / h);
        let value = a * z[i]
            + b * z[i + 1]
            + ((a * a * a - a) * m[i] + (b * b * b - b) * m[i + 1]) * h * h / 6.0;
        let slope = (z[i + 1] - z[i]) / h
            + ((1.0 - 3.0 * a * a) * m[i] + (3.0 * b * b - 1.0) * m[i + 1]) * h / 6.0;
        (value, slope)
    }
}
