//! Prints the firmware's case table, evaluated on the host, in the firmware's
//! `case GROUP.ITEM HEX…` format. Built with `nalgebra` without `std`, so f32 `powf`,
//! `tanh`, `sqrt` come from the `libm` crate as on the Cortex-M4F: any difference
//! from the firmware's output is then the core's, not the math library's.

#[path = "../../src/cases/mod.rs"]
mod cases;

fn main() {
    let fixture = match cases::Fixture::decode() {
        Ok(fixture) => fixture,
        Err(e) => {
            eprintln!("the ball's blobs do not decode: {e}");
            std::process::exit(1);
        }
    };
    cases::evaluate_all(&fixture, &mut |group, item, bits| {
        let words: Vec<String> = bits.iter().map(|b| format!("{b:08x}")).collect();
        println!("case {group}.{item} {}", words.join(" "));
    });
    println!("end");
}
