//! The force search's tunable parameters ([`SEARCH`]) and how values set them, in a preset's
//! `[task.place.search]` (checked by the preset's rule when it is validated, so that a tuned
//! value the preset refuses, a floor band above its wall, is refused naming the field).

use fairgrasp_env::config::{SEARCH_BOUNDS, SearchParams};

use crate::controls::params::{Param, ParamValues, Scale};

const fn bounds(i: usize) -> [f64; 2] {
    [SEARCH_BOUNDS[i].lo, SEARCH_BOUNDS[i].hi]
}

/// The search's parameters, every one open: the four the first grid tuned and the descent
/// speed, the press's admittance, the largest radius and the floor check.
pub const SEARCH: [Param; 8] = [
    Param {
        name: "descend_speed",
        unit: "m/s",
        accepts: bounds(0),
        range: [0.003, 0.05],
        scale: Scale::Log,
        doc: "descent speed until the touch and into the pocket",
    },
    Param {
        name: "contact_force",
        unit: "N",
        accepts: bounds(1),
        range: [0.5, 5.0],
        scale: Scale::Log,
        doc: "upward wrist force that counts as a touch",
    },
    Param {
        name: "admittance",
        unit: "m/s per N",
        accepts: bounds(2),
        range: [0.001, 0.05],
        scale: Scale::Log,
        doc: "vertical speed of the press per newton below the touch force",
    },
    Param {
        name: "pitch",
        unit: "m per turn",
        accepts: bounds(3),
        range: [0.001, 0.006],
        scale: Scale::Linear,
        doc: "the spiral's growth per turn",
    },
    Param {
        name: "speed",
        unit: "m/s",
        accepts: bounds(4),
        range: [0.005, 0.05],
        scale: Scale::Log,
        doc: "the spiral's speed along its path",
    },
    Param {
        name: "max_radius",
        unit: "m",
        accepts: bounds(5),
        range: [0.005, 0.03],
        scale: Scale::Linear,
        doc: "the largest spiral radius before the cube is let go",
    },
    Param {
        name: "floor_band",
        unit: "m",
        accepts: [0.0002, 0.02],
        range: [0.001, 0.008],
        scale: Scale::Linear,
        doc: "a touch this near the floor counts as the cube in (at most the wall's height)",
    },
    Param {
        name: "check_floor",
        unit: "",
        accepts: [0.0, 1.0],
        range: [0.0, 1.0],
        scale: Scale::Switch,
        doc: "a touch while inserting, above the floor band, resumes the spiral",
    },
];

/// The squaring control's parameters: the squaring's own six, then its search's
/// (`search_…`).
pub const SQUARE: [Param; 14] = [
    Param {
        name: "offset",
        unit: "m",
        accepts: [0.05, 0.3],
        range: [0.07, 0.14],
        scale: Scale::Linear,
        doc: "the squaring spot's distance from the pocket's centre",
    },
    Param {
        name: "speed",
        unit: "m/s",
        accepts: [0.001, 0.05],
        range: [0.005, 0.05],
        scale: Scale::Log,
        doc: "speed down onto the table and back",
    },
    Param {
        name: "force",
        unit: "N",
        accepts: [0.5, 30.0],
        range: [2.0, 20.0],
        scale: Scale::Log,
        doc: "the press stops at this upward wrist force",
    },
    Param {
        name: "press",
        unit: "m",
        accepts: [-0.01, 0.01],
        range: [-0.002, 0.005],
        scale: Scale::Linear,
        doc: "how far past standing flat the TCP presses",
    },
    Param {
        name: "hold",
        unit: "s",
        accepts: [0.0, 3.0],
        range: [0.0, 1.0],
        scale: Scale::Linear,
        doc: "how long the press is held",
    },
    Param {
        name: "squeeze",
        unit: "N",
        accepts: [0.2, 100.0],
        range: [0.3, 5.0],
        scale: Scale::Log,
        doc: "the squeeze per finger while pressing and holding",
    },
    renamed(SEARCH[0], "search_descend_speed"),
    renamed(SEARCH[1], "search_contact_force"),
    renamed(SEARCH[2], "search_admittance"),
    renamed(SEARCH[3], "search_pitch"),
    renamed(SEARCH[4], "search_speed"),
    renamed(SEARCH[5], "search_max_radius"),
    renamed(SEARCH[6], "search_floor_band"),
    renamed(SEARCH[7], "search_check_floor"),
];

/// The switching search's parameters: the band that reads a tilted cube, then the two
/// searches' (`pose_…`, `tilted_…`).
pub const SWITCH: [Param; 17] = [
    Param {
        name: "tilt_band",
        unit: "m",
        accepts: [0.0001, 0.01],
        range: [0.0005, 0.005],
        scale: Scale::Linear,
        doc: "a first touch this far from the rim's height reads as a tilted cube",
    },
    renamed(SEARCH[0], "pose_descend_speed"),
    renamed(SEARCH[1], "pose_contact_force"),
    renamed(SEARCH[2], "pose_admittance"),
    renamed(SEARCH[3], "pose_pitch"),
    renamed(SEARCH[4], "pose_speed"),
    renamed(SEARCH[5], "pose_max_radius"),
    renamed(SEARCH[6], "pose_floor_band"),
    renamed(SEARCH[7], "pose_check_floor"),
    renamed(SEARCH[0], "tilted_descend_speed"),
    renamed(SEARCH[1], "tilted_contact_force"),
    renamed(SEARCH[2], "tilted_admittance"),
    renamed(SEARCH[3], "tilted_pitch"),
    renamed(SEARCH[4], "tilted_speed"),
    renamed(SEARCH[5], "tilted_max_radius"),
    renamed(SEARCH[6], "tilted_floor_band"),
    renamed(SEARCH[7], "tilted_check_floor"),
];

/// `p` under the name `name` (a search's parameter in a larger control's list).
const fn renamed(p: Param, name: &'static str) -> Param {
    Param { name, ..p }
}

/// The search's current values as [`SEARCH`] names them (a floor band of `None` as half the
/// wall, `wall_height` \[m\]).
pub fn search_values(s: &SearchParams, wall_height: f64) -> ParamValues {
    let band = s.floor_band.unwrap_or(0.5 * wall_height);
    [
        ("descend_speed", s.descend_speed),
        ("contact_force", s.contact_force),
        ("admittance", s.admittance),
        ("pitch", s.pitch),
        ("speed", s.speed),
        ("max_radius", s.max_radius),
        ("floor_band", band),
        ("check_floor", if s.check_floor { 1.0 } else { 0.0 }),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect()
}

/// Sets the search's values in `values` whose names start with `prefix` (the rest of the name
/// one of [`SEARCH`]'s); the env's rule checks them when it is validated.
pub fn set_search(s: &mut SearchParams, values: &ParamValues, prefix: &str) {
    for (name, &v) in values {
        let Some(field) = name.strip_prefix(prefix) else {
            continue;
        };
        match field {
            "descend_speed" => s.descend_speed = v,
            "contact_force" => s.contact_force = v,
            "admittance" => s.admittance = v,
            "pitch" => s.pitch = v,
            "speed" => s.speed = v,
            "max_radius" => s.max_radius = v,
            "floor_band" => s.floor_band = Some(v),
            "check_floor" => s.check_floor = v > 0.5,
            _ => {}
        }
    }
}
