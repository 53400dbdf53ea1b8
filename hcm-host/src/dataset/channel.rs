//! Channels: the groups of columns an instrument fills together. A high-speed camera
//! gives position and orientation (and perhaps differentiated velocities) at its frames,
//! a force sensor gives force (and perhaps torque) at its own rate, so one row may hold
//! some channels and leave the others empty: "not sampled at this row".
//!
//! Inside a [`Sample`] a channel that was not sampled holds NaN in every component.
//! NaN rather than `Option` because every consumer written before rows could be partial
//! reads the arrays directly (`sample.force[2]`): with NaN they keep compiling and,
//! on complete data, compute exactly what they did, while on partial data a consumer
//! that forgets to check gets NaN — loud — instead of a silent 0. Each command checks
//! the channels it needs before it reads ([`super::needs`]), and the reader never
//! produces NaN otherwise (a `NaN` cell is an error), so NaN means "not sampled" and
//! nothing else.

use super::schema::{COLUMNS, FIRST_NUMERIC};
use super::Sample;

/// One group of columns, filled whole or left empty in a row.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Channel {
    /// Position of the centre of mass `px, py, pz` (m).
    Position,
    /// Orientation quaternion `qw, qx, qy, qz` (–).
    Orientation,
    /// Linear velocity `vx, vy, vz` (m/s).
    Velocity,
    /// Angular velocity `wx, wy, wz` (rad/s).
    AngularVelocity,
    /// Contact force `fx, fy, fz` (N).
    Force,
    /// Contact torque `tx, ty, tz` (N·m).
    Torque,
}

impl Channel {
    /// Every channel, in column order.
    pub const ALL: [Channel; 6] = [
        Channel::Position,
        Channel::Orientation,
        Channel::Velocity,
        Channel::AngularVelocity,
        Channel::Force,
        Channel::Torque,
    ];

    /// The channel's name in messages, e.g. `angular velocity`.
    pub fn name(self) -> &'static str {
        match self {
            Channel::Position => "position",
            Channel::Orientation => "orientation",
            Channel::Velocity => "velocity",
            Channel::AngularVelocity => "angular velocity",
            Channel::Force => "force",
            Channel::Torque => "torque",
        }
    }

    /// Indices in `COLUMNS` of the channel's columns.
    pub fn columns(self) -> std::ops::Range<usize> {
        let (first, count) = match self {
            Channel::Position => (3, 3),
            Channel::Orientation => (6, 4),
            Channel::Velocity => (10, 3),
            Channel::AngularVelocity => (13, 3),
            Channel::Force => (16, 3),
            Channel::Torque => (19, 3),
        };
        first..first + count
    }

    /// Indices into [`super::schema::sample_values`] of the channel's numbers.
    pub fn values(self) -> std::ops::Range<usize> {
        let columns = self.columns();
        columns.start - FIRST_NUMERIC..columns.end - FIRST_NUMERIC
    }

    /// The column names, e.g. `fx, fy, fz`.
    pub(crate) fn column_list(self) -> String {
        COLUMNS[self.columns()]
            .iter()
            .map(|column| column.name)
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The channel in a message: `force (fx, fy, fz)`.
    pub(crate) fn described(self) -> String {
        format!("{} ({})", self.name(), self.column_list())
    }

    /// The channel holding column `index` of [`COLUMNS`], if it is a channel's.
    pub(crate) fn of_column(index: usize) -> Option<Channel> {
        Channel::ALL
            .into_iter()
            .find(|channel| channel.columns().contains(&index))
    }

    /// The channel's numbers in `sample`.
    pub fn read(self, sample: &Sample) -> &[f64] {
        match self {
            Channel::Position => &sample.position,
            Channel::Orientation => &sample.orientation,
            Channel::Velocity => &sample.velocity,
            Channel::AngularVelocity => &sample.angular_velocity,
            Channel::Force => &sample.force,
            Channel::Torque => &sample.torque,
        }
    }

    /// The channel's numbers in `sample`, to fill or clear.
    fn write(self, sample: &mut Sample) -> &mut [f64] {
        match self {
            Channel::Position => &mut sample.position,
            Channel::Orientation => &mut sample.orientation,
            Channel::Velocity => &mut sample.velocity,
            Channel::AngularVelocity => &mut sample.angular_velocity,
            Channel::Force => &mut sample.force,
            Channel::Torque => &mut sample.torque,
        }
    }
}

impl std::fmt::Display for Channel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl Sample {
    /// A sample at `time` (s) in which no channel was sampled (every number NaN): the
    /// starting point for a camera frame or a force-sensor row.
    pub fn unsampled(time: f64) -> Self {
        let mut sample = Sample::at_rest(time);
        for channel in Channel::ALL {
            sample.clear(channel);
        }
        sample
    }

    /// Whether `channel` was sampled at this row: every component a finite number.
    pub fn has(&self, channel: Channel) -> bool {
        channel.read(self).iter().all(|value| value.is_finite())
    }

    /// Whether `channel` is marked "not sampled": every component NaN.
    pub fn lacks(&self, channel: Channel) -> bool {
        channel.read(self).iter().all(|value| value.is_nan())
    }

    /// Marks `channel` as not sampled at this row.
    pub fn clear(&mut self, channel: Channel) {
        channel.write(self).fill(f64::NAN);
    }
}

/// Two samples are equal when every number is, a channel not sampled (NaN) equal to a
/// channel not sampled: the equality a read-back is checked with.
impl PartialEq for Sample {
    fn eq(&self, other: &Self) -> bool {
        let same = |a: f64, b: f64| a == b || (a.is_nan() && b.is_nan());
        let (a, b) = (
            super::schema::sample_values(self),
            super::schema::sample_values(other),
        );
        a.iter().zip(&b).all(|(&a, &b)| same(a, b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_channels_cover_every_numeric_column_but_time_once() {
        let mut covered: Vec<usize> = Channel::ALL
            .iter()
            .flat_map(|channel| channel.columns())
            .collect();
        covered.sort_unstable();
        let expected: Vec<usize> = (FIRST_NUMERIC + 1..COLUMNS.len()).collect();
        assert_eq!(covered, expected);
        assert_eq!(Channel::Force.column_list(), "fx, fy, fz");
        assert_eq!(Channel::Orientation.column_list(), "qw, qx, qy, qz");
        assert_eq!(Channel::of_column(12), Some(Channel::Velocity));
        assert_eq!(Channel::of_column(2), None);
    }

    #[test]
    fn a_channel_read_and_written_is_the_samples_own() {
        let mut sample = Sample::at_rest(1.0);
        sample.force = [1.0, 2.0, 3.0];
        for channel in Channel::ALL {
            let values = super::super::schema::sample_values(&sample);
            assert_eq!(channel.read(&sample), &values[channel.values()]);
        }
        assert!(sample.has(Channel::Force) && !sample.lacks(Channel::Force));
        sample.clear(Channel::Force);
        assert!(sample.lacks(Channel::Force) && !sample.has(Channel::Force));
        assert!(sample.has(Channel::Position));
        let empty = Sample::unsampled(2.0);
        assert!(Channel::ALL.iter().all(|&c| empty.lacks(c)));
        assert_eq!(empty, Sample::unsampled(2.0));
        assert_ne!(empty, Sample::at_rest(2.0));
    }
}
