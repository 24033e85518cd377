//! The drive callers of the step counter and of the C library's `rand()` (MBDyn's `meter`,
//! `closest next`, `random`) and the `fourier series` (issue 12):
//! `tests/mbdyn_files/counter_drives.mbd` against closed forms and MBDyn 1.7.3, retried
//! steps, a second run, and the errors.

use crate::common;

use common::mbdyn::{read_test_file, test_file as path};
use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::element::drive::c_rand::{CRand, RAND_MAX};
use romdyn::input::mbdyn::{build, parse_text, MbdynModel};

fn text() -> String {
    std::fs::read_to_string(path("counter_drives.mbd")).unwrap_or_else(|e| panic!("{e}"))
}

fn from_text(t: &str) -> Result<MbdynModel, String> {
    from_named_text(t, "counter_drives.mbd")
}

fn from_named_text(t: &str, name: &str) -> Result<MbdynModel, String> {
    parse_text(t, &path(name)).and_then(|d| build(&d)).map_err(|e| e.to_string())
}

/// (x, ẋ) of each node at the end of a run.
fn final_x(m: &MbdynModel) -> Vec<(f64, f64)> {
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    (0..m.model.nodes.len()).map(|k| report.final_state.node_frame(&asm.dofs, k).kin).map(|k| (k.x[0], k.xdot[0])).collect()
}

/// Crank-Nicolson on ẍ = f_k from rest: (x, ẋ) after the last step of `h`.
fn trapezoid(f: &[f64], h: f64) -> (f64, f64) {
    let (mut x, mut v) = (0.0, 0.0);
    for w in f.windows(2) {
        let v_new = v + 0.5 * h * (w[0] + w[1]);
        x += 0.5 * h * (v + v_new);
        v = v_new;
    }
    (x, v)
}

/// The drives of the file at steps 0..=20 (h = 0.01 s), from their definitions.
fn drive_values() -> [Vec<f64>; 5] {
    let times: Vec<f64> = (0..=20).map(|k| k as f64 * 0.01).collect();
    let meter = (0..=20).map(|k| f64::from(u8::from(k == 3 || k == 6))).collect();
    let closest = (0..=20).map(|k| f64::from(u8::from([2, 4, 7, 9, 11, 14, 16, 18].contains(&k)))).collect();
    let fourier = times
        .iter()
        .map(|&t| {
            let s = t - 0.005;
            if s < 0.0 || s >= 0.4 * std::f64::consts::PI {
                return 0.5;
            }
            0.5 + 1.0 + 2.0 * (10.0 * s).cos() + 3.0 * (10.0 * s).sin() + 4.0 * (20.0 * s).cos() + 5.0 * (20.0 * s).sin()
        })
        .collect();
    // srand(7) (drive caller 4's seed; drive caller 5 does not seed again): the cards draw
    // r0, r1 (4) and r2, r3 (5) when read, their copies by `reference` r4, r5 (force 4) and
    // r6, r7 (force 5); then each step draws for the drives in that order, 4 and its copy
    // every 2 steps, 5 and its copy every step.
    let mut g = CRand::new(7);
    let r: Vec<u64> = (0..100).map(|_| u64::from(g.next_rand())).collect();
    let steps = [2usize, 1, 2, 1];
    let draw = |j: usize, m: usize| -> u64 {
        let before: usize = steps.iter().map(|s| (m - 1) / s).sum();
        r[8 + before + steps[..j].iter().filter(|s| m % **s == 0).count()]
    };
    let max = u64::from(RAND_MAX);
    let random = |j: usize, base: usize, amplitude: f64, mean: f64, (t0, t1): (f64, f64)| -> Vec<f64> {
        (0..=20usize)
            .map(|k| {
                if !(t0..=t1).contains(&(k as f64 * 0.01)) {
                    return mean;
                }
                let m = steps[j] * (k / steps[j]);
                let last = if m == 0 { r[base + 1] } else { draw(j, m) };
                mean + amplitude * (2.0 * ((r[base] + last) % max) as f64 / max as f64 - 1.0)
            })
            .collect()
    };
    [meter, closest, fourier, random(2, 4, 2.0, 1.0, (0.025, 0.135)), random(3, 6, 1.0, 0.0, (0.0, f64::INFINITY))]
}

#[test]
fn driven_bodies_move_as_the_closed_forms_and_as_mbdyn() {
    let m = read_test_file("counter_drives.mbd");
    let end = final_x(&m);
    // MBDyn 1.7.3 (built from github:alex-marinov/mbdyn, glibc's rand()) on this file,
    // `output precision: 16`, last row of its .mov (t = 0.2 s): x and ẋ of nodes 1 to 5.
    let mbdyn = [
        (3.1000000000000003e-03, 2.0000000000000000e-02),
        (7.9000000000000008e-03, 8.0000000000000002e-02),
        (1.6167538409379473e-01, 1.1859242877837679e+00),
        (1.9036880722562780e-02, 1.9548850432519105e-01),
        (-3.0227593943062399e-03, 7.3566788015798305e-03),
    ];
    let closed = drive_values().map(|f| trapezoid(&f, 0.01));
    for (k, ((&(x, v), (mx, mv)), (cx, cv))) in end.iter().zip(mbdyn).zip(closed).enumerate() {
        eprintln!("node {}: x {x:.16e} (MBDyn {mx:.16e}, closed {cx:.16e}), ẋ {v:.16e} (MBDyn {mv:.16e}, closed {cv:.16e})", k + 1);
        // Closed form: the trapezoidal sums of the drives' values (Crank-Nicolson, exact
        // for a free body) from the exact initial acceleration; the file's initial
        // derivatives are solved to 1e-6 (MBDyn fails at 1e-12), which moves ẋ by up to
        // h/2 · 1e-6 = 5e-9 where the force is not 0 at t = 0 (nodes 3 to 5; measured
        // 5e-9 to 9.4e-9, MBDyn's the same): 2e-8.
        assert!((x - cx).abs() < 2e-8 && (v - cv).abs() < 2e-8, "node {}: {x}, {v} against {cx}, {cv}", k + 1);
        // MBDyn: the same method, steps and drive values (the same initial derivatives
        // too): measured within 2e-16; asserted to 1e-14.
        assert!((x - mx).abs() < 1e-14 && (v - mv).abs() < 1e-14, "node {}: {x}, {v} against MBDyn {mx}, {mv}", k + 1);
    }
    // (A wrong draw would move a random body's ẋ by up to 2 h A = 0.04 m/s.)
    // The same model run again starts from the drives' initial memory: the same numbers.
    assert_eq!(final_x(&m), end);
}

#[test]
fn a_seed_in_another_place_changes_the_numbers() {
    // Seeding drive caller 5 with 8 changes what it and every drive after it draws (the
    // copies' and all the steps' numbers come from srand(8)): nodes 4 and 5 move
    // otherwise, nodes 1 to 3 as before.
    let t = text().replacen("random, 1., 0., 0., forever;", "random, 1., 0., 0., forever, seed, 8;", 1);
    let end = final_x(&from_text(&t).unwrap());
    let base = final_x(&read_test_file("counter_drives.mbd"));
    assert_eq!(end[..3], base[..3]);
    assert!((end[3].1 - base[3].1).abs() > 1e-6 && (end[4].1 - base[4].1).abs() > 1e-6, "{:?} {:?}", end, base);
    // `seed, time` (srand(time(NULL)), as MBDyn) is read; its numbers cannot be compared
    // with anything, only bounded: node 4's force is in [−1, 3) N on [0.025, 0.135] s and 1 N
    // elsewhere, so ẋ(0.2 s) lies in [0.09 − 0.11, 0.09 + 3 · 0.11] m/s, node 5's in ±0.2.
    let t = text().replacen("seed, 7;", "seed, time;", 1);
    let end = final_x(&from_text(&t).unwrap());
    assert!((-0.02..=0.42).contains(&end[3].1) && end[4].1.abs() <= 0.2, "{end:?}");
}

#[test]
fn bad_counter_drives_name_the_place_and_what_was_expected() {
    let base = text();
    let cases = [
        ("steps, 3;", "steps, 0;", "steps must be at least 1"),
        ("const, 0.0237;", "const, -0.0237;", "increment must be positive"),
        ("10., 2, 2., 2., 3., 4., 5., 2, 0.5;", "10., 0, 2., 2., 3., 4., 5., 2, 0.5;", "number of terms"),
        ("10., 2, 2., 2., 3., 4., 5., 2, 0.5;", "10., 2, 2., 2., 3., 4., 5., -1, 0.5;", "number of cycles"),
        ("10., 2, 2., 2., 3., 4., 5., 2, 0.5;", "10., 2, 2., 2., 3., 4., 5., 2;", "initial value"),
        ("seed, 7;", "seed, seven;", "seed (an integer, or time)"),
    ];
    for (old, new, expected) in cases {
        assert!(base.contains(old), "{old}");
        let e = match from_text(&base.replacen(old, new, 1)) {
            Err(e) => e,
            Ok(_) => panic!("{new} must be refused"),
        };
        assert!(e.contains("counter_drives.mbd:") && e.contains(expected), "{new}: {e}");
    }
}

#[test]
fn postponed_drives_are_copies_of_later_cards_as_in_mbdyn() {
    let m = read_test_file("postponed_drives.mbd");
    let end = final_x(&m);
    // MBDyn 1.7.3 on tests/mbdyn_files/postponed_drives.mbd, `output precision: 16`, last
    // row of its .mov (t = 0.2 s): x and ẋ of nodes 1 to 3. romdyn measured within 6e-18;
    // asserted to 1e-14. Node 1's numbers need its copy's draws after every card's and
    // every `reference` copy's (made when MBDyn first calls the force): with the copy's
    // draws at the force's place (before card 2's copy) ẋ would be 0.1507 m/s instead of
    // 0.1818 (the same arithmetic in Python on glibc's rand()).
    let mbdyn = [
        (1.6284719118791556e-02, 1.8184453861633368e-01),
        (6.4865714898428310e-04, -8.5271242650868107e-04),
        (1.6167538409379473e-01, 1.1859242877837679e+00),
    ];
    for (k, (&(x, v), (mx, mv))) in end.iter().zip(mbdyn).enumerate() {
        eprintln!("node {}: x {x:.16e} (MBDyn {mx:.16e}), ẋ {v:.16e} (MBDyn {mv:.16e})", k + 1);
        assert!((x - mx).abs() < 1e-14 && (v - mv).abs() < 1e-14, "node {}: {x}, {v} against MBDyn {mx}, {mv}", k + 1);
    }
    // Node 3's postponed fourier series is counter_drives.mbd's drive caller 3.
    let base = final_x(&read_test_file("counter_drives.mbd"));
    assert_eq!(end[2], base[2]);
    // `method: ms, postponed, 7` took card 7's radius 1 (Crank-Nicolson): 0.6 would
    // change the motion.
    let text = std::fs::read_to_string(path("postponed_drives.mbd")).unwrap();
    let other = final_x(&from_named_text(&text.replacen("drive caller: 7, const, 1.;", "drive caller: 7, const, 0.6;", 1), "postponed_drives.mbd").unwrap());
    assert!((other[2].0 - end[2].0).abs() > 1e-6, "{other:?}");

    // A postponed drive caller needs the card; inside a card, one read before it.
    let cases = [
        ("postponed, 1;", "postponed, 11;", "no drive caller card 11"),
        ("drive caller: 2, random, 1., 0., 0., forever, seed, 7;", "drive caller: 2, postponed, 3;", "no drive caller card 3 is read before"),
        // (A radius reading the model's state through `postponed` is evaluated at every
        // step since 2026-12-03: tests/mbdyn/varying_radius.rs.)
    ];
    for (old, new, expected) in cases {
        assert!(text.contains(old), "{old}");
        let e = match from_named_text(&text.replacen(old, new, 1), "postponed_drives.mbd") {
            Err(e) => e,
            Ok(_) => panic!("{new} must be refused"),
        };
        assert!(e.contains("postponed_drives.mbd:") && e.contains(expected), "{new}: {e}");
    }
}

#[test]
fn template_drive_caller_cards_are_copied_as_in_mbdyn() {
    let end = final_x(&read_test_file("template_drive_cards.mbd"));
    // MBDyn 1.7.3 on tests/mbdyn_files/template_drive_cards.mbd, `output precision: 16`,
    // last row of its .mov (t = 0.2 s): x and ẋ of nodes 1 to 5. romdyn measured within
    // 6e-18; asserted to 1e-14.
    let mbdyn = [
        (3.1000000000000003e-03, 2.0000000000000000e-02),
        (7.9000000000000008e-03, 8.0000000000000002e-02),
        (1.6167538409379473e-01, 1.1859242877837679e+00),
        (1.0015217595551316e-02, 1.3377596813655107e-01),
        (2.9370438880466712e-03, 3.7998281107463070e-03),
    ];
    for (k, (&(x, v), (mx, mv))) in end.iter().zip(mbdyn).enumerate() {
        eprintln!("node {}: x {x:.16e} (MBDyn {mx:.16e}), ẋ {v:.16e} (MBDyn {mv:.16e})", k + 1);
        assert!((x - mx).abs() < 1e-14 && (v - mv).abs() < 1e-14, "node {}: {x}, {v} against MBDyn {mx}, {mv}", k + 1);
    }
    let base = final_x(&read_test_file("counter_drives.mbd"));
    assert_eq!(end[..3], base[..3]);

    let text = std::fs::read_to_string(path("template_drive_cards.mbd")).unwrap();
    let cases = [
        ("template drive caller: 8, \"3\",", "template drive caller: 8, \"4\",", "template drive caller 8: unsupported dimension 4"),
        ("reference, 9;", "reference, 10;", "template drive caller 10 is not defined"),
        ("template drive caller: 9, 3,", "template drive caller: 8, 3,", "template drive caller 8 is defined twice"),
        ("single, 1., 0., 0., reference, 3;", "single, 1., 0., reference, 3;", "template drive caller vector"),
    ];
    for (old, new, expected) in cases {
        assert!(text.contains(old), "{old}");
        let e = match from_named_text(&text.replacen(old, new, 1), "template_drive_cards.mbd") {
            Err(e) => e,
            Ok(_) => panic!("{new} must be refused"),
        };
        assert!(e.contains("template_drive_cards.mbd:") && e.contains(expected), "{new}: {e}");
    }
}

/// The times of the steps `m` writes to the `.mov` (the `.out`'s `Out` column, as MBDyn's)
/// after checking that node 1 has that many rows.
fn written_times(m: &MbdynModel, name: &str) -> Vec<f64> {
    let dir = common::cli::temp_dir(name);
    let prefix = dir.join("counter_drives");
    let mut files = romdyn::analysis::RunFiles::create(&prefix, "counter_drives.mbd", &m.model, &m.problem).unwrap();
    let report = run(&m.model, &m.problem, &mut files).unwrap();
    files.finish(&report).unwrap();
    let out = std::fs::read_to_string(dir.join("counter_drives.out")).unwrap();
    let written: Vec<f64> = out.lines().filter(|l| l.starts_with("Step ") && l.ends_with(" 1")).map(|l| l.split_whitespace().nth(2).unwrap().parse().unwrap()).collect();
    let mov = std::fs::read_to_string(dir.join("counter_drives.mov")).unwrap();
    assert_eq!(mov.lines().filter(|l| l.split_whitespace().next() == Some("1")).count(), written.len(), "{out}");
    written
}

#[test]
fn an_output_meter_chooses_the_written_steps() {
    // `output meter: DRIVE` in control data (dataman2.cc `DataManager::Output`: a step is
    // written when the drive is not 0). A meter every 3 steps: steps 0, 3, …, 18 of 20 (7
    // rows); MBDyn's own drives/drivecallers/meter and closestnext (output meter: meter
    // every 10 steps, closest next every 0.01 s, at 1 ms) give 101 and 102 rows in MBDyn
    // 1.7.3 and in romdyn, equal to MBDyn's 7 printed digits (5e-8) throughout.
    let t = text().replacen("    output precision: 16;", "    output precision: 16;\n    output meter: meter, 0., forever, steps, 3;", 1);
    let m = from_text(&t).unwrap();
    let times = written_times(&m, "meter");
    assert!(times.len() == 7 && times.iter().enumerate().all(|(k, t)| (t - 0.03 * k as f64).abs() < 1e-12), "{times:?}");
    // A closest next every 0.045 s: steps 0 and 1 (its start, reached at step 0 and moved
    // on only at step 2), then the first steps past 0.045, 0.09, 0.135, 0.18: 5, 9 or 10
    // (whether 9 steps of 0.01 reach 0.09 is a matter of rounding), 14, 18 or 19.
    let t = text().replacen("    output precision: 16;", "    output precision: 16;\n    output meter: closest next, 0., forever, const, 0.045;", 1);
    let times = written_times(&from_text(&t).unwrap(), "closest");
    let steps: Vec<usize> = times.iter().map(|t| (t / 0.01).round() as usize).collect();
    assert!(steps.len() == 6 && steps[..3] == [0, 1, 5] && [9, 10].contains(&steps[3]) && steps[4] == 14 && [18, 19].contains(&steps[5]), "{steps:?}");
    // With `output frequency` too, MBDyn stops: romdyn as well.
    let t = text().replacen("    output precision: 16;", "    output frequency: 2;\n    output meter: meter, 0., forever, steps, 3;", 1);
    let e = from_text(&t).err().expect("refused");
    assert!(e.contains("counter_drives.mbd:") && e.contains("already given"), "{e}");
}
