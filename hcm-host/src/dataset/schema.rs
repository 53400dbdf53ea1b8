//! The columns of the measured-data CSV format — names, order, SI units and meaning — in
//! one place. The writer's header, the reader's column lookup, the README table and the
//! order of a [`Sample`]'s numbers all come from `COLUMNS`.

use super::Sample;

/// One column of the format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Column {
    /// Header name, exactly as it appears in a file (case-sensitive).
    pub(crate) name: &'static str,
    /// SI unit; `–` for text and dimensionless columns.
    pub(crate) unit: &'static str,
    /// What the value is.
    pub(crate) meaning: &'static str,
}

const fn c(name: &'static str, unit: &'static str, meaning: &'static str) -> Column {
    Column {
        name,
        unit,
        meaning,
    }
}

/// Number of columns the format defines.
pub(crate) const COLUMN_COUNT: usize = 22;

/// Number of numeric columns: every column after `run` and `body`.
pub(crate) const NUMERIC_COUNT: usize = COLUMN_COUNT - FIRST_NUMERIC;

/// Index in [`COLUMNS`] of `run`.
pub(crate) const RUN: usize = 0;
/// Index in [`COLUMNS`] of `body`.
pub(crate) const BODY: usize = 1;
/// Index in `COLUMNS` of `time`, the first numeric column.
pub const TIME: usize = 2;
/// Index in [`COLUMNS`] of the first numeric column; numeric column `i` of a
/// [`Sample`] (see [`sample_values`]) is `COLUMNS[FIRST_NUMERIC + i]`.
pub(crate) const FIRST_NUMERIC: usize = TIME;

/// The columns in the order the writer emits them. All vectors are in the world frame.
pub(crate) const COLUMNS: [Column; COLUMN_COUNT] = [
    c("run", "–", "run identifier (text), e.g. `0`, `trial_03`"),
    c("body", "–", "body name (text), e.g. `ball`"),
    c(
        "time",
        "s",
        "sample time, strictly increasing within one (run, body)",
    ),
    c("px", "m", "position of the centre of mass, x"),
    c("py", "m", "position of the centre of mass, y"),
    c("pz", "m", "position of the centre of mass, z"),
    c(
        "qw",
        "–",
        "orientation (body to world) unit quaternion, scalar w",
    ),
    c("qx", "–", "orientation unit quaternion, x"),
    c("qy", "–", "orientation unit quaternion, y"),
    c("qz", "–", "orientation unit quaternion, z"),
    c("vx", "m/s", "linear velocity of the centre of mass, x"),
    c("vy", "m/s", "linear velocity of the centre of mass, y"),
    c("vz", "m/s", "linear velocity of the centre of mass, z"),
    c("wx", "rad/s", "angular velocity, x"),
    c("wy", "rad/s", "angular velocity, y"),
    c("wz", "rad/s", "angular velocity, z"),
    c("fx", "N", "contact force on the body, x"),
    c("fy", "N", "contact force on the body, y"),
    c("fz", "N", "contact force on the body, z"),
    c(
        "tx",
        "N·m",
        "contact torque on the body about its centre of mass, x",
    ),
    c(
        "ty",
        "N·m",
        "contact torque on the body about its centre of mass, y",
    ),
    c(
        "tz",
        "N·m",
        "contact torque on the body about its centre of mass, z",
    ),
];

/// The numeric columns of a sample, in `COLUMNS` order (`time`, `px` … `tz`).
pub fn sample_values(sample: &Sample) -> [f64; NUMERIC_COUNT] {
    let [px, py, pz] = sample.position;
    let [qw, qx, qy, qz] = sample.orientation;
    let [vx, vy, vz] = sample.velocity;
    let [wx, wy, wz] = sample.angular_velocity;
    let [fx, fy, fz] = sample.force;
    let [tx, ty, tz] = sample.torque;
    [
        sample.time,
        px,
        py,
        pz,
        qw,
        qx,
        qy,
        qz,
        vx,
        vy,
        vz,
        wx,
        wy,
        wz,
        fx,
        fy,
        fz,
        tx,
        ty,
        tz,
    ]
}

/// The inverse of [`sample_values`].
pub(crate) fn sample_from_values(values: [f64; NUMERIC_COUNT]) -> Sample {
    let [time, px, py, pz, qw, qx, qy, qz, vx, vy, vz, wx, wy, wz, fx, fy, fz, tx, ty, tz] = values;
    Sample {
        time,
        position: [px, py, pz],
        orientation: [qw, qx, qy, qz],
        velocity: [vx, vy, vz],
        angular_velocity: [wx, wy, wz],
        force: [fx, fy, fz],
        torque: [tx, ty, tz],
    }
}

/// The header row, `run,body,time,px,…,tz`.
pub fn csv_header() -> String {
    COLUMNS.map(|column| column.name).join(",")
}

/// The schema as a Markdown table (column, unit, meaning), as in the README and the
/// module documentation.
pub fn schema_markdown() -> String {
    let mut table = String::from("| column | unit | meaning |\n|---|---|---|\n");
    for column in COLUMNS {
        table.push_str(&format!(
            "| `{}` | {} | {} |\n",
            column.name, column.unit, column.meaning
        ));
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_header_is_the_documented_one() {
        assert_eq!(
            csv_header(),
            "run,body,time,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,fx,fy,fz,tx,ty,tz"
        );
        assert_eq!(COLUMNS[RUN].name, "run");
        assert_eq!(COLUMNS[BODY].name, "body");
        assert_eq!(COLUMNS[TIME].name, "time");
    }

    #[test]
    fn each_number_lands_in_its_named_column() {
        let sample = sample_from_values(core::array::from_fn(|i| i as f64));
        let values = sample_values(&sample);
        let at = |name: &str| {
            let index = COLUMNS.iter().position(|c| c.name == name).unwrap();
            values[index - FIRST_NUMERIC]
        };
        assert_eq!(at("time"), sample.time);
        assert_eq!(at("pz"), sample.position[2]);
        assert_eq!(at("qw"), sample.orientation[0]);
        assert_eq!(at("qz"), sample.orientation[3]);
        assert_eq!(at("vy"), sample.velocity[1]);
        assert_eq!(at("wx"), sample.angular_velocity[0]);
        assert_eq!(at("fx"), sample.force[0]);
        assert_eq!(at("tz"), sample.torque[2]);
        assert_eq!(sample_from_values(values), sample);
    }

    #[test]
    fn the_module_documentation_shows_this_table() {
        let documentation: String = include_str!("mod.rs")
            .lines()
            .filter_map(|line| line.strip_prefix("//!"))
            .map(|line| format!("{}\n", line.strip_prefix(' ').unwrap_or(line)))
            .collect();
        assert!(
            documentation.contains(&schema_markdown()),
            "update the table in dataset/mod.rs to:\n{}",
            schema_markdown()
        );
    }
}
