"""Task panels and docks: find contacts, the contact table, joints, haptic trial."""
