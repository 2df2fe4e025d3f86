//! Inputs set while their switch says they are not read (`vd_in` set while `drive_source =
//! prescribed`): a master that connects an input and forgets the switch gets a wrong answer, so
//! the FMU says so, once per input and run.

use super::values::ValueSet;
use super::variable::{InputSwitch, ModelTable};

/// Which governed inputs were set while unread, and which were already reported.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UnreadInputs {
    /// Set during initialization, judged when it ends (the switch may be set after the input).
    set_early: u64,
    reported: u64,
}

impl UnreadInputs {
    /// Back to a fresh run (fmi2Instantiate, fmi2Reset).
    pub fn clear(&mut self) {
        *self = UnreadInputs::default();
    }

    /// The input `value_reference` was set. Before the run starts it is only noted; during the
    /// run the message for an unread input comes back, once.
    pub fn set(
        &mut self,
        table: &ModelTable,
        values: &ValueSet,
        value_reference: u32,
        running: bool,
    ) -> Option<String> {
        let (bit, governed) = governed_by(table, value_reference)?;
        if !running {
            self.set_early |= bit;
            return None;
        }
        self.report(table, values, bit, governed)
    }

    /// The run starts: the messages for inputs set during initialization that the
    /// configuration does not read, joined.
    pub fn start(&mut self, table: &ModelTable, values: &ValueSet) -> Option<String> {
        let early = self.set_early;
        let messages: Vec<String> = table
            .input_switches
            .iter()
            .enumerate()
            .filter(|(i, _)| early & (1 << i) != 0)
            .filter_map(|(i, governed)| self.report(table, values, 1 << i, governed))
            .collect();
        self.set_early = 0;
        (!messages.is_empty()).then(|| messages.join("; "))
    }

    fn report(
        &mut self,
        table: &ModelTable,
        values: &ValueSet,
        bit: u64,
        governed: &InputSwitch,
    ) -> Option<String> {
        let switch = table.by_name(governed.switch)?.value_reference;
        let item = values.item(switch);
        if item == governed.item || self.reported & bit != 0 {
            return None;
        }
        self.reported |= bit;
        Some(format!(
            "{input} is set but not read: {switch} = {item} ({number}) ignores it; expected {switch} = {wanted} ({wanted_number}) for the model to follow {input}",
            input = governed.input,
            switch = governed.switch,
            number = values.integer(switch),
            wanted = governed.item,
            wanted_number = switch_number(table, governed).unwrap_or(0),
        ))
    }
}

fn governed_by(table: &ModelTable, value_reference: u32) -> Option<(u64, &InputSwitch)> {
    let name = table.variable(value_reference)?.name;
    table
        .input_switches
        .iter()
        .enumerate()
        .find(|(_, s)| s.input == name)
        .map(|(i, s)| (1 << i, s))
}

fn switch_number(table: &ModelTable, governed: &InputSwitch) -> Option<i32> {
    use super::variable::Kind;
    let Kind::Switch { type_name, .. } = table.by_name(governed.switch)?.kind else {
        return None;
    };
    table.enum_type(type_name)?.value_of(governed.item)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::transverse::table::{vr, TABLE};

    fn drive_from_input(values: &mut ValueSet) {
        values.set(vr::DRIVE_SOURCE, 2.0);
    }

    #[test]
    fn an_input_set_while_unread_is_reported_once_per_run() {
        let values = ValueSet::start(&TABLE);
        let mut unread = UnreadInputs::default();
        let message = unread.set(&TABLE, &values, vr::VD_IN, true).unwrap();
        assert!(message.contains("drive_source = input (2)"), "{message}");
        assert_eq!(unread.set(&TABLE, &values, vr::VD_IN, true), None);
        unread.clear();
        assert!(unread.set(&TABLE, &values, vr::VD_IN, true).is_some());
    }

    #[test]
    fn the_switch_may_follow_the_input_during_initialization() {
        let mut values = ValueSet::start(&TABLE);
        let mut unread = UnreadInputs::default();
        assert_eq!(unread.set(&TABLE, &values, vr::VD_IN, false), None);
        drive_from_input(&mut values);
        assert_eq!(unread.start(&TABLE, &values), None);
        assert_eq!(unread.set(&TABLE, &values, vr::VD_IN, true), None);
    }

    #[test]
    fn an_input_set_during_initialization_and_never_read_is_reported_at_the_start() {
        let values = ValueSet::start(&TABLE);
        let mut unread = UnreadInputs::default();
        assert_eq!(unread.set(&TABLE, &values, vr::VD_IN, false), None);
        let message = unread.start(&TABLE, &values).unwrap();
        assert!(
            message.starts_with("vd_in is set but not read"),
            "{message}"
        );
        // Parameters are not governed inputs.
        assert_eq!(unread.set(&TABLE, &values, vr::VD, true), None);
    }
}
