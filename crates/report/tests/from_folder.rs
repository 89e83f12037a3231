//! The page drawn again from a report folder's data (`osrl report --from`) is the page of the
//! run, byte for byte: every experiment at a tiny size, written, read back, drawn again.

use osrl_experiments::{reproduce, ChangeSizes, E9Sizes, Quiet, RobotSizes, Sizes};
use osrl_report::{render, write_report, Page};
use std::path::Path;

fn tiny() -> Sizes {
    let robot = RobotSizes {
        minutes: 0.1,
        babble_minutes: Some(0.05),
        eval_every_minutes: 0.05,
    };
    Sizes {
        toy_seeds: 1,
        learned_seeds: 1,
        ablation_seeds: 1,
        analytical_seconds: 8.0,
        eval_periods: 1,
        payload_kg: 0.5,
        arm_instants: 3,
        planar3: robot.clone(),
        sarcos7: robot,
        e8: ChangeSizes {
            nominal_minutes: 0.05,
            changed_minutes: 0.05,
            after_minutes: 0.05,
            eval_every_minutes: 0.05,
        },
        // E9 on planar3 (its table and figure are drawn again too).
        e9: E9Sizes {
            planar3_seeds: 1,
            sarcos7_seeds: 0,
            paths_per_kind: 1,
        },
    }
}

/// Every file under `dir` (relative paths), sorted.
fn files(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                out.push(p.strip_prefix(dir).unwrap().display().to_string());
            }
        }
    }
    out.sort();
    out
}

#[test]
fn the_page_drawn_from_the_folder_is_the_page_of_the_run() {
    let root = std::env::temp_dir().join(format!("osrl-report-from-{}", std::process::id()));
    let (a, b) = (root.join("run"), root.join("again"));
    let rep = reproduce(&tiny(), true, &Quiet).unwrap();
    write_report(&a, &rep).unwrap();
    // The data read back are the run's: numbers bit for bit.
    let page = Page::load(&a).unwrap();
    assert_eq!(page.results, rep.results);
    assert_eq!(page.figures, rep.figures);
    assert_eq!(page.analytical.len(), rep.analytical.len());
    for ((dir, s), r) in page.analytical.iter().zip(&rep.analytical) {
        assert_eq!(*dir, r.case.dir());
        assert_eq!(s, &r.run.series, "{dir}");
    }
    assert_eq!(page.learned.len(), 2, "seed 0's series of both robots");
    for (robot, s) in &page.learned {
        let mut want = rep.learned[robot].clone();
        want.command_seconds.clear(); // wall times: not part of the folder
        assert_eq!(s, &want, "{robot}");
    }
    // E8's timelines ran on both robots, their figure is on the page.
    assert_eq!(page.results.e8.len(), 2, "{:?}", rep.failed);
    assert!(a.join("E8/planar3_change.svg").exists());
    let text = std::fs::read_to_string(a.join("results.json")).unwrap();
    assert_eq!(text, rep.results.to_json().unwrap());
    // Drawn again elsewhere: the same page and the same figures, byte for byte.
    render(&b, &page).unwrap();
    let html = std::fs::read(a.join("index.html")).unwrap();
    assert_eq!(std::fs::read(b.join("index.html")).unwrap(), html);
    let drawn: Vec<String> = files(&b);
    assert!(
        drawn.iter().filter(|f| f.ends_with(".svg")).count() >= 20,
        "{drawn:?}"
    );
    for f in &drawn {
        assert_eq!(
            std::fs::read(b.join(f)).unwrap(),
            std::fs::read(a.join(f)).unwrap(),
            "{f}"
        );
    }
    let html = String::from_utf8(html).unwrap();
    assert!(html.contains("<h2>Summary</h2>") && html.find("Summary") < html.find("<h2>E1"));
    // A folder without what the page is drawn from: an error naming the file.
    std::fs::remove_file(a.join("figures.json")).unwrap();
    let err = Page::load(&a).unwrap_err().to_string();
    assert!(err.contains("figures.json"), "{err}");
    std::fs::remove_dir_all(&root).unwrap();
}
