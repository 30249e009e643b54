"""Tests FreeCAD's own test runner finds (Init.py registers this module):
`freecadcmd -t contactwb.freecad_tests`. The full suites are under tests/."""
import unittest

import FreeCAD


class ContactsWorkbenchTest(unittest.TestCase):
    def test_two_blocks_make_one_planar_fit(self):
        import Part
        from contactwb.document import analysis
        lower = Part.makeBox(10, 10, 10)
        upper = Part.makeBox(4, 4, 4, FreeCAD.Vector(2, 2, 10))
        result = analysis.find_contacts_in_shapes([("lower", lower), ("upper", upper)])
        self.assertEqual([(c.type, c.a, c.b) for c in result.contacts], [("PLF", "lower", "upper")])
        self.assertAlmostEqual(result.contacts[0].area, 16.0, places=6)
