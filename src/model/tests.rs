use super::*;

#[test]
fn new_models_share_one_empty_tree() {
    let a = Model::new("a");
    let b = Model::new("b");
    assert_eq!(a.worldbody(), b.worldbody());
    assert_eq!(a.name(), "a");
    assert_eq!(Model::new("").name(), "unnamed_model");
}
