//! The inline data checks' pairs, each verdict MuJoCo 4.0.0's (the refused model
//! with the message the check words, its twin compiled).

use super::super::tests::assert_pairs;

#[test]
fn a_meshs_inline_vertices_and_faces_are_judged_in_mujocos_order() {
    let pairs = [
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 nan"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 -inf"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 -1e3"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" face="0 2 1 0 1 3 0 3 2 1 2 3"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" /></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" texcoord="0 0 1 0 0 1 1 1"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" face="0 2 1 0 1 3 0 3 2 1 2 9"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" normal="0 0 1"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" face="0 2 1 0 1 3 0 3 2 1 2 -1"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" face="0 2 1 0 1 3 0 3 2 1 2 3"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" face="0 2 1 0"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" builtin="sphere" params="1"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" texcoord="0 0 1"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" texcoord="0 0 1 0 0 1 1 1"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" texcoord="0 0 1 1"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" normal="0 0 1 1"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1 0"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 nan"/></asset></mujoco>"#,
            r#"<mujoco><compiler discardvisual="true"/><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 nan"/></asset></mujoco>"#,
        ),
    ];
    assert_pairs("mesh-inline-data", &pairs);
}

#[test]
fn a_mesh_without_faces_is_judged_by_its_hull_as_mujoco_judges_it() {
    let pairs = [
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 0 0 0 0 0 0 0 0 0"/></asset><worldbody><geom type="mesh" mesh="m"/></worldbody></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/></asset><worldbody><geom type="mesh" mesh="m"/></worldbody></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1e-16 0 0 0 1e-16 0 0 0 0"/></asset></mujoco>"#,
            r#"<mujoco><compiler discardvisual="true"/><asset><mesh name="m" vertex="0 0 0 1e-7 0 0 0 1e-7 0 0 0 1e-7"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 2 0 0 3 0 0"/></asset><worldbody><geom type="mesh" mesh="m"/></worldbody></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/></asset><worldbody><geom type="mesh" mesh="m"/></worldbody></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="1 1 1 1 1 1 1 1 1 1 1 1.0000001"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1e-6"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 1 1 0"/></asset><worldbody><geom type="mesh" mesh="m"/></worldbody></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 1 1 1e-3"/></asset><worldbody><geom type="mesh" mesh="m"/></worldbody></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1e-16 0 0 0 1 0 0 0 1"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 1 1 0" maxhullvert="4" inertia="shell"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" maxhullvert="4"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1e-9 0 0 0 1e-9 0 0 0 1e-9"/></asset><worldbody><geom type="mesh" mesh="m"/></worldbody></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1e-4 0 0 0 1e-4 0 0 0 1e-4"/></asset><worldbody><geom type="mesh" mesh="m"/></worldbody></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" scale="1e-9 1e-9 1e-9"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" scale="1e-4 1e-4 1e-4"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" scale="0 0 1"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" scale="-1 1 1"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" scale="0 1 1"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" scale="0 1 1" inertia="shell"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" scale="1 1 0" inertia="convex"/></asset><worldbody><geom type="mesh" mesh="m"/></worldbody></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" scale="1 1 1e-3" inertia="convex"/></asset><worldbody><geom type="mesh" mesh="m"/></worldbody></mujoco>"#,
        ),
        (
            r#"<mujoco><default><mesh scale="0 1 1"/></default><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/></asset></mujoco>"#,
            r#"<mujoco><default><mesh scale="0 1 1" inertia="shell"/></default><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" scale="1 0 1" inertia="legacy"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" scale="1 0 1" refquat="1 1 0 0" inertia="shell"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1e-7 0 0 0 1e-7 0 0 0 1e-7"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1e-7 0 0 0 1e-7 0 0 0 1e-7" inertia="shell"/></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" scale="1e-6 1e-6 1e-6"/></asset></mujoco>"#,
            r#"<mujoco><asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1" scale="1e-4 1e-4 1e-4"/></asset></mujoco>"#,
        ),
    ];
    assert_pairs("mesh-inline-data", &pairs);
}

#[test]
fn a_flexs_dim_elements_vertices_and_bodies_are_judged_in_mujocos_order() {
    let pairs = [
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="4" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2 0 1"></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="0" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2 0"></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="1" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 1 2"></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2 0"></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2 1 2 0"></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0 0" element="0 1 2"></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b b" element="0 1 3"></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 5"></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 -1"></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="2 1 0"></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 1"></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2 2 0 2"></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2 2 0 1"></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="1" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 0"></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="1" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1"></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b nope" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b world b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b nope" vertex="0 0 0 1 0 0 0 1 0" element="0 1 1"></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body><replicate count="2"><body name="r"><geom size=".1"/></body></replicate></worldbody><deformable><flex name="f" dim="2" body="b r0 r1" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"/></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><asset><material name="mat"/></asset><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" material="mat" body="b b c" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"/></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"></flex></deformable></mujoco>"#,
        ),
    ];
    assert_pairs("flex-inline-data", &pairs);
}

#[test]
fn a_flexs_poisson_ratio_is_judged_where_mujoco_judges_it() {
    let pairs = [
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"><elasticity young="1" poisson="0.7"/></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"><elasticity poisson="0.7"/></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="1" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 1 2"><elasticity young="1" poisson="0.5"/></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="1" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 1 2"><elasticity young="1" poisson="0.4999"/></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b nope" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"><elasticity young="1" poisson="0.7" elastic2d="bend" thickness="0.1"/></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"><elasticity young="1" poisson="0.3" elastic2d="bend" thickness="0.1"/></flex></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 1"><elasticity young="1" poisson="0.7"/></flex></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2"><elasticity young="0" poisson="0.7"/></flex></deformable></mujoco>"#,
        ),
    ];
    assert_pairs("flex-inline-data", &pairs);
}

#[test]
fn a_skins_inline_data_and_bone_weights_are_judged_in_mujocos_order() {
    let pairs = [
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0" vertweight="1"/></skin></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><asset><skin vertex="0 0 0 1 0 0 0 1 0"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></asset></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><asset><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></asset></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"></skin></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2" texcoord="0 0 1 0"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2" texcoord="0 0 1 0 0 1"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0 1" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2 0"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1"/></skin></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1" vertweight="1 1"/><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="2" vertweight="1"/></skin></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 5" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 -1" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 0"/></skin></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1e-14"/></skin></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1e-16"/></skin></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 -1"/><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="2" vertweight="2"/></skin></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1" vertweight="1 1"/></skin></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 nan" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 3"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 -1" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></deformable></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><asset><skin vertex="0 0 0 1 0 0 0 1 0" face="0 -1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></asset></mujoco>"#,
            r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><asset><skin vertex="0 0 0 1 0 0 0 1 0" face="2 1 0 0 1 2"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></asset></mujoco>"#,
        ),
    ];
    assert_pairs("skin-inline-data", &pairs);
}

#[test]
fn a_flexcomps_poisson_ratio_out_of_range_is_refused_with_a_positive_young() {
    let pairs = [
        (
            r#"<mujoco><worldbody><flexcomp name="f" type="grid" count="3 3 1" spacing=".1 .1 .1" dim="2"><elasticity young="100" poisson="0.5"/></flexcomp></worldbody></mujoco>"#,
            r#"<mujoco><worldbody><flexcomp name="f" type="grid" count="3 3 1" spacing=".1 .1 .1" dim="2"><elasticity young="100" poisson="0.3"/></flexcomp></worldbody></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><flexcomp name="f" type="grid" count="3 3 1" spacing=".1 .1 .1" dim="2"><elasticity young="1e-300" poisson="-0.1"/></flexcomp></worldbody></mujoco>"#,
            r#"<mujoco><worldbody><flexcomp name="f" type="grid" count="3 3 1" spacing=".1 .1 .1" dim="2"><elasticity young="0" poisson="0.5"/></flexcomp></worldbody></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><flexcomp name="f" type="grid" count="3 3 1" spacing=".1 .1 .1" dim="2"><elasticity young="100" poisson="2"/></flexcomp></worldbody></mujoco>"#,
            r#"<mujoco><worldbody><flexcomp name="f" type="grid" count="3 3 1" spacing=".1 .1 .1" dim="2"><elasticity young="100" poisson="nan"/></flexcomp></worldbody></mujoco>"#,
        ),
        (
            r#"<mujoco><worldbody><flexcomp name="f" type="grid" count="3 3 1" spacing=".1 .1 .1" dim="2"><elasticity young="100" poisson="0.5" elastic2d="none"/></flexcomp></worldbody></mujoco>"#,
            r#"<mujoco><worldbody><flexcomp name="f" type="grid" count="3 3 1" spacing=".1 .1 .1" dim="2"><elasticity young="-1" poisson="0.5"/></flexcomp></worldbody></mujoco>"#,
        ),
    ];
    assert_pairs("flex-poisson", &pairs);
}
