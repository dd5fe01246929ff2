//! The frictions a new user hit (issue 21), each shown removed: mixed number lists in
//! `element!`, ...

use mjcf::{Element, Model, element};

#[test]
fn element_macro_mixes_integers_and_floats_in_a_list() {
    let mixed = element!("geom", type = "box", size = [2, 2, 0.1], rgba = [1, 0.5, 0, 1]);
    let floats = Element::new("geom")
        .attr("type", "box")
        .attr("size", [2.0, 2.0, 0.1])
        .attr("rgba", [1.0, 0.5, 0.0, 1.0]);
    assert_eq!(mixed, floats);
    let mut m = Model::new("m");
    let cam = element!("camera", name = "c", xyaxes = [0, 1, 0, -0.5, 0, 1]);
    let cam = m.add_mut(&m.worldbody(), cam).unwrap();
    assert_eq!(m.floats(&cam, "xyaxes").unwrap(), [0.0, 1.0, 0.0, -0.5, 0.0, 1.0]);
}

#[test]
fn element_macro_lists_take_variables_repeats_and_trailing_commas() {
    let (x, n) = (0.25_f32, 3_u32);
    let e = element!("site", pos = [x, n, -1,], size = [0.1; 3], euler = [0.0, 0.0, 1.0],);
    let expected = Element::new("site")
        .attr("pos", [0.25, 3.0, -1.0])
        .attr("size", [0.1, 0.1, 0.1])
        .attr("euler", [0.0, 0.0, 1.0]);
    assert_eq!(e, expected);
    // A value that only starts with a list is a value as a whole.
    let e = element!("site", pos = [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]][1]);
    assert_eq!(e, Element::new("site").attr("pos", [4.0, 5.0, 6.0]));
    assert_eq!(element!("site",), Element::new("site"));
}
