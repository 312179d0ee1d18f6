"""Contacts in simulation: each contact mode derived once, a consistent mode and friction regime, the
contact problem over every touching contact, impacts and the transitions between modes."""
