//! Carrying out one [`Edit`] on a model.

use crate::error::ErrorKind;
use crate::model::Model;
use crate::schema::Role;

use super::builder::Builder;
use super::palette::{palette, value};
use super::pick::{elements, m_default_kind, valid};
use super::recipe::{Edit, MAX_DEPTH};
use super::repair::remove_repaired;

impl Builder {
    /// Carries out one edit; `None` when it does not apply or would leave more than
    /// `allowed` problems.
    pub(super) fn edit(&mut self, m: &Model, edit: &Edit, allowed: usize) -> Option<Model> {
        match edit {
            Edit::Add(step) => self.step(m, step, 0, "", allowed),
            Edit::Set { target, attr } => {
                let targets = elements(m, |e| !palette(e.tag, e.in_default).is_empty());
                let t = target.of(&targets)?;
                let entry = attr.which.of(palette(t.tag, t.in_default))?;
                let v = value(t.kind, entry, attr)?;
                let next = m.set_attr(&t.loc, entry.name, v).ok()?;
                valid(&next, allowed).then_some(next)
            }
            Edit::Rename { target, name } => {
                let targets = elements(m, |e| {
                    e.kind.identifier().is_some()
                        && !e.frame
                        && !e.in_frame
                        && e.kind != m_default_kind()
                });
                let t = target.of(&targets)?;
                let attr = t.kind.attr(t.kind.identifier()?).name;
                let next = match name {
                    None => {
                        // Only elements nothing refers to, that need no name.
                        let needs_name = matches!(
                            t.kind.role(),
                            Some(Role::DefaultClass | Role::Material | Role::Mesh)
                        );
                        if needs_name || !m.references_to(&t.loc).is_empty() {
                            return None;
                        }
                        m.clear_attr(&t.loc, attr).ok()?
                    }
                    Some(w) => {
                        let mut found = None;
                        for k in 1..=6 {
                            let n = if k == 1 {
                                w.text().to_string()
                            } else {
                                format!("{}_{k}", w.text())
                            };
                            match m.set_attr(&t.loc, attr, n.as_str()) {
                                Ok(r) => {
                                    found = Some(r);
                                    break;
                                }
                                Err(e)
                                    if matches!(
                                        e.kind(),
                                        ErrorKind::DuplicateIdentifier { .. }
                                    ) => {}
                                Err(_) => return None,
                            }
                        }
                        found?
                    }
                };
                valid(&next, allowed).then_some(next)
            }
            Edit::Remove { target } => {
                let targets = elements(m, |e| e.removable);
                let t = target.of(&targets)?;
                remove_repaired(m, &t.loc, allowed)
            }
            Edit::Detach { scope } => {
                let s = scope.of(&m.scope_paths())?.clone();
                let next = m.detach(&s).ok()?;
                valid(&next, allowed).then_some(next)
            }
            Edit::RenameScope { scope, to } => {
                let s = scope.of(&m.scope_paths())?.clone();
                let next = m.rename_scope(&s, to.model_name()).ok()?;
                valid(&next, allowed).then_some(next)
            }
            Edit::IncludeCopy { source, override_attributes } => {
                self.copies += 1;
                let prefix = format!("c{}_", self.copies);
                let source = self.model(source, MAX_DEPTH, &prefix);
                let next = m.include_copy(&source, *override_attributes).ok()?;
                valid(&next, allowed).then_some(next)
            }
        }
    }
}
