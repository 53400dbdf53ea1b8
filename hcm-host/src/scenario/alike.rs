//! Contacts a scenario declares alike: the links of one mechanism (or several bodies)
//! landing on the same fixed body with the same law, parameters, friction and
//! tangential effects. The scenario says they are one material, so a fit or a
//! diagnosis changes them together; a lone body's contact is alike only with itself.

use super::Model;

impl Model {
    /// The contacts alike with contact `contact` (itself included, in file order):
    /// those between the same fixed body and a moving body whose normal law (with its
    /// effects), friction and tangential effects are equal to its. Only itself where
    /// neither or both of its bodies are fixed, or where `contact` is out of range
    /// (then none).
    pub fn alike_contacts(&self, contact: usize) -> Vec<usize> {
        let Some(this) = self.contacts.get(contact) else {
            return Vec::new();
        };
        let fixed = |b: usize| self.bodies[b].fixed;
        let partner = match (fixed(this.body_1), fixed(this.body_2)) {
            (true, false) => this.body_1,
            (false, true) => this.body_2,
            _ => return vec![contact],
        };
        (self.contacts.iter().enumerate())
            .filter(|(_, c)| {
                let other = c.body_1 + c.body_2 - partner;
                (c.body_1 == partner || c.body_2 == partner)
                    && !fixed(other)
                    && c.model.normal == this.model.normal
                    && c.model.friction == this.model.friction
                    && c.model.tangential == this.model.tangential
            })
            .map(|(i, _)| i)
            .collect()
    }

    /// The moving body of contact `contact` against its fixed partner `partner`.
    pub fn mover_of(&self, contact: usize, partner: usize) -> usize {
        let c = &self.contacts[contact];
        c.body_1 + c.body_2 - partner
    }
}

#[cfg(test)]
mod tests {
    use crate::scenario::Scenario;
    use std::path::Path;

    const ELBOW: &str = include_str!("../../scenarios/elbow_toss.toml");

    /// The elbow's two links land on the one table with one law: alike. Either link's
    /// contact given another friction leaves each alike with itself alone.
    #[test]
    fn links_on_one_table_with_one_law_are_alike_until_one_differs() {
        let read = |sets: &[String]| {
            let scenario = Scenario::parse(Path::new("elbow_toss.toml"), ELBOW, sets).unwrap();
            scenario.model().unwrap()
        };
        let model = read(&[]);
        assert_eq!(model.alike_contacts(0), vec![0, 1]);
        assert_eq!(model.alike_contacts(1), vec![0, 1]);
        assert!(model.alike_contacts(2).is_empty());
        let other = read(&["contact.1.friction.mu_static=0.4".to_owned()]);
        assert_eq!(other.alike_contacts(0), vec![0]);
        assert_eq!(other.alike_contacts(1), vec![1]);
    }
}
