//! A robot that does not fit the maze's passages (issue 37, item 4): `validate
//! --robot-width` and `apply` warn and exit 0; `apply` reads the footprint of the scene's
//! `Robot` after the draw when no width is given, and says nothing when the scene has none.

use vrep_maze::draw::{
    self, ApplyOptions, Backend, BackendError, BoundingBox, Edit, ObjectInfo, Picture, Survey,
    SurveyNames,
};
use vrep_maze::generate::Algorithm;
use vrep_maze::sim::Scene;

use crate::support::backend::Kind;
use crate::support::backend_tests;
use crate::support::bin;
use crate::support::cli::Serve;
use crate::support::layouts::course_layout;

backend_tests!(the_scene_s_robot_is_read_after_the_draw_and_warned_of);

/// A connection whose scene holds a robot of `model` box named `Robot` (the emulator models
/// no model bounding boxes): every other call goes to the emulator.
struct WithRobot {
    inner: Box<dyn Backend>,
    model: BoundingBox,
    asked: Vec<String>,
}

impl Backend for WithRobot {
    fn idle_rates(&mut self) -> Result<draw::IdleRates, BackendError> {
        self.inner.idle_rates()
    }
    fn survey(&mut self, names: &SurveyNames<'_>) -> Result<Survey, BackendError> {
        self.inner.survey(names)
    }
    fn objects(&mut self) -> Result<Vec<ObjectInfo>, BackendError> {
        self.inner.objects()
    }
    fn bounding_boxes(
        &mut self,
        handles: &[i32],
    ) -> Result<Vec<Option<BoundingBox>>, BackendError> {
        self.inner.bounding_boxes(handles)
    }
    fn int_signals(&mut self, names: &[&str]) -> Result<Vec<Option<i32>>, BackendError> {
        self.inner.int_signals(names)
    }
    fn set_int_signals(&mut self, signals: &[(&str, Option<i32>)]) -> Result<(), BackendError> {
        self.inner.set_int_signals(signals)
    }
    fn copy_paste(&mut self, groups: &[Vec<i32>]) -> Result<Vec<Vec<i32>>, BackendError> {
        self.inner.copy_paste(groups)
    }
    fn edit(&mut self, edits: &[Edit]) -> Result<(), BackendError> {
        self.inner.edit(edits)
    }
    fn set_idle_fps(&mut self, fps: i32, saved: Option<i32>) -> Result<(), BackendError> {
        self.inner.set_idle_fps(fps, saved)
    }
    fn stop_simulation(&mut self) -> Result<(), BackendError> {
        self.inner.stop_simulation()
    }
    fn round_trips(&self) -> usize {
        self.inner.round_trips()
    }
    fn describe(&self) -> String {
        format!("{} with a robot", self.inner.describe())
    }
    fn model_box(&mut self, name: &str) -> Result<Option<BoundingBox>, BackendError> {
        self.asked.push(name.to_string());
        Ok((name == "Robot").then_some(self.model))
    }
}

/// The warnings of drawing the 3 x 3 course maze (1 m cells) with `options` on `scene`.
fn warnings(scene: &mut dyn Backend, options: ApplyOptions) -> Vec<String> {
    let layout = course_layout(Algorithm::Dfs, 3, 3, 1);
    let job = draw::Job {
        layout: &layout,
        picture: Picture::of(&layout, draw::DrawMode::Copies).unwrap(),
        options,
        create_missing: false,
        save_scene: None,
    };
    draw::run(scene, &job, &mut |_| {}).unwrap().drawn.warnings
}

fn the_scene_s_robot_is_read_after_the_draw_and_warned_of(kind: Kind) {
    let s = kind.serve(Scene::course(), 0);
    let name = kind.name();
    // 1.4 m long, 1.2 m wide: its narrower side is wider than the lines are apart
    let wide = BoundingBox {
        min: [-0.7, -0.6, 0.0],
        max: [0.7, 0.6, 0.1],
    };
    let mut scene = WithRobot {
        inner: s.connect(),
        model: wide,
        asked: vec![],
    };
    let said = warnings(&mut scene, ApplyOptions::default());
    assert_eq!(scene.asked, ["Robot"], "{name}");
    assert!(
        said.iter().any(|w| w.starts_with(
            "`Robot` in the scene (its model's bounding box): a robot 1.200 m wide does not fit between the lines, 1.000 m apart"
        )),
        "{name}: {said:?}"
    );
    // a width given is not read; another name is asked by its name
    let given = ApplyOptions {
        robot: draw::robot::RobotCheck {
            name: "Robot".into(),
            width: Some(0.2),
        },
        ..Default::default()
    };
    let said = warnings(&mut scene, given);
    assert!(
        said.iter().all(|w| !w.contains("robot")),
        "{name}: {said:?}"
    );
    let rover = ApplyOptions {
        robot: draw::robot::RobotCheck {
            name: "Rover".into(),
            width: None,
        },
        ..Default::default()
    };
    let said = warnings(&mut scene, rover);
    assert_eq!(scene.asked, ["Robot", "Rover"], "{name}");
    assert!(
        said.iter().all(|w| !w.contains("robot")),
        "{name}: {said:?}"
    );
    // the emulator's own scene has no Robot: nothing is said (the legacy server serves
    // one client at a time)
    drop(scene);
    let mut plain = s.connect();
    let said = warnings(plain.as_mut(), ApplyOptions::default());
    assert!(
        said.iter().all(|w| !w.contains("robot")),
        "{name}: {said:?}"
    );
    drop(plain);
    s.shutdown();
}

#[test]
fn validate_warns_of_a_robot_wider_than_the_passages_and_exits_0() {
    let dir = tempfile::tempdir().unwrap();
    let mouse = dir.path().join("mouse.json").display().to_string();
    bin()
        .args([
            "generate",
            "--preset",
            "micromouse",
            "--posts",
            "--seed",
            "3",
            "-o",
        ])
        .arg(&mouse)
        .assert()
        .success();
    // 0.18 m cells less 0.012 m posts: 0.168 m; the course robot is about 0.2 m wide
    let out = bin()
        .args(["validate", &mouse, "--robot-width", "0.2"])
        .assert()
        .success()
        .get_output()
        .clone();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.contains(&format!(
            "warning: {mouse}: a robot 0.200 m wide does not fit the passages: 0.168 m between the posts (0.180 m cells)"
        )),
        "{stderr}"
    );
    let json = bin()
        .args(["validate", &mouse, "--robot-width", "0.2", "--json"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let report: serde_json::Value = serde_json::from_slice(&json).unwrap();
    let warnings = report["files"][0]["warnings"].to_string();
    assert!(warnings.contains("0.168 m between the posts"), "{report}");
    // a narrower robot fits, and without the option nothing is checked
    for args in [&["--robot-width", "0.1"][..], &[]] {
        let out = bin()
            .args(["validate", &mouse])
            .args(args)
            .assert()
            .success()
            .get_output()
            .clone();
        assert!(
            !String::from_utf8_lossy(&out.stderr).contains("warning"),
            "{args:?}"
        );
    }
    bin()
        .args(["validate", &mouse, "--robot-width", "-0.2"])
        .assert()
        .code(2)
        .stderr(predicates::str::contains("a length must be a positive"));
}

#[test]
fn apply_warns_of_a_robot_width_given_that_does_not_fit_and_exits_0() {
    let dir = tempfile::tempdir().unwrap();
    let maze = dir.path().join("m.json").display().to_string();
    bin()
        .args(["generate", "--size", "3x3", "--seed", "1", "-o", &maze])
        .assert()
        .success();
    let server = Serve::start(
        &[
            "--listen",
            "127.0.0.1:0",
            "--timing",
            "instant",
            "--idle-fps",
            "0",
        ],
        1,
    );
    let out = bin()
        .args([
            "apply",
            &maze,
            "--port",
            &server.port(),
            "--robot-width",
            "1.5",
        ])
        .assert()
        .success()
        .get_output()
        .clone();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.contains(
            "warning: a robot 1.500 m wide does not fit between the lines, 1.000 m apart"
        ),
        "{stderr}"
    );
}
