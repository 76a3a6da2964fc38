//! Where the walk starts: the scene-file type each model's table is deserialized into
//! (`contactlab::scene::any::Scene::from_table` and `scene::moving::MovingScene::from_table`), and
//! the few keys read outside those types.

use crate::scene_keys::walk::Row;

/// The keys of one model.
#[derive(Debug, Clone)]
pub struct ModelKeys {
    /// The model's name (`contactlab::scene::Scene::model`): the section's heading.
    pub model: &'static str,
    /// What the file's `model` key says and how the table selects this format among that
    /// model's (`None`: the key names this model).
    pub selected_by: Option<(&'static str, &'static str)>,
    /// The scene-file struct.
    pub root: String,
    /// Its file under `src/`.
    pub file: String,
    /// What the model is: the meaning of its `model` key (else the struct's doc).
    pub doc: String,
    pub rows: Vec<Row>,
}

/// (model, the scene-file struct, its file under `src/`), in the order of
/// `contactlab::scene::any::MODELS`.
pub const MODELS: [(&str, &str, &str); 6] = [
    ("rod", "RodSceneFile", "scene/rod.rs"),
    ("plane", "PlaneSceneFile", "scene/plane.rs"),
    ("dynamic", "DynamicSceneFile", "scene/dynamic/format.rs"),
    (
        "moving_string",
        "MovingStringSceneFile",
        "scene/moving/string.rs",
    ),
    ("disc_particle", "DiscSceneFile", "scene/moving/disc.rs"),
    (
        "rotating_plate",
        "RotatingPlateSceneFile",
        "scene/moving/plate.rs",
    ),
];

/// Formats a model's table takes besides its own, chosen by the table's shape: (the name
/// `contactlab::scene::Scene::model` gives them, the `model` the file names, how the table
/// selects the format, the scene-file struct, its file under `src/`).
pub const VARIANTS: [(&str, &str, &str, &str, &str); 1] = [(
    "multibody",
    "dynamic",
    "with `[[body]]` sections (an array of tables; one `[body]` table is the one-body \
     [`dynamic`](#dynamic) scene)",
    "MultibodySceneFile",
    "scene/multibody/format.rs",
)];

/// Keys no type of the solver declares: the solver reads the rod's `[exact]` as a free-form
/// table (it does not use it), and the verification crate's `verify scene` reads its `solution`
/// (`verification/src/rod/study.rs`, `ExactSpec`). The walk of `src/` cannot see them, so they
/// are listed here, after the row of their table.
pub fn extra_rows(model: &str) -> Vec<(&'static str, Row)> {
    match model {
        "rod" => vec![(
            "exact",
            Row {
                path: "exact.solution".into(),
                aliases: Vec::new(),
                ty: "string".into(),
                requirement: "required (in `[exact]`)".into(),
                meaning: "The exact solution `verify scene` measures the run against (it then \
                          writes `errors.json`); the solver does not read it."
                    .into(),
                values: [
                    ("rod_constant_data", "the constant-data family, its data taken from the scene"),
                    ("paper_4_6", "the paper's solution (4.6), p0 = 6 (docs/quasistatic.md), with its own data"),
                    ("paper_4_7", "the paper's solution (4.7), p0 = 2 (docs/quasistatic.md), with its own data"),
                    ("rod_manufactured_switching", "a manufactured solution whose contact switches"),
                    ("rod_manufactured_receding", "a manufactured solution whose contact recedes"),
                ]
                .iter()
                .map(|(v, d)| (v.to_string(), d.to_string()))
                .collect(),
                origin: "verification/src/rod/study.rs: ExactSpec.solution".into(),
            },
        )],
        _ => Vec::new(),
    }
}
