"""ISO 286 limits and fits: a fit code such as H7/g6 at a nominal diameter
gives the hole's and the shaft's limit deviations, the fit's smallest and
largest clearance and its class (clearance, transition, interference).

Tables from ISO 286-1:2010 (standard tolerance grades IT01..IT18, table 1;
the rules deriving hole deviations from shaft deviations, 4.2.2 and the Δ
rule) and ISO 286-2:2010 (the shafts' fundamental deviations), for nominal
sizes over 0 up to 500 mm. Letters covered: shafts a b c d e f g h js k m n
p r s t u and holes A B C D E F G H JS K M N P R S T U; other letters (cd, j,
v, x, y, z, za...) are refused by name rather than guessed. All deviations in
micrometres (µm).

    fit = iso286.fit("H7/g6", 20.0)
    fit.hole, fit.shaft       # (0, 21), (-20, -7): (lower, upper) deviations
    fit.clearance             # (7, 41): smallest and largest clearance
    fit.fit_class             # "clearance"
"""
import bisect
import re
from dataclasses import dataclass
from typing import Tuple

MAX_DIAMETER = 500.0  # mm: ISO 286-2's deviations of the letters below stop here

# Main size ranges (ISO 286-1 table 1): over the previous limit up to and including this one.
_MAIN = (3, 6, 10, 18, 30, 50, 80, 120, 180, 250, 315, 400, 500)

# Standard tolerance grades, µm, per main range (ISO 286-1 table 1).
_IT = {
    "01": (0.3, 0.4, 0.4, 0.5, 0.6, 0.6, 0.8, 1, 1.2, 2, 2.5, 3, 4),
    "0": (0.5, 0.6, 0.6, 0.8, 1, 1, 1.2, 1.5, 2, 3, 4, 5, 6),
    "1": (0.8, 1, 1, 1.2, 1.5, 1.5, 2, 2.5, 3.5, 4.5, 6, 7, 8),
    "2": (1.2, 1.5, 1.5, 2, 2.5, 2.5, 3, 4, 5, 7, 8, 9, 10),
    "3": (2, 2.5, 2.5, 3, 4, 4, 5, 6, 8, 10, 12, 13, 15),
    "4": (3, 4, 4, 5, 6, 7, 8, 10, 12, 14, 16, 18, 20),
    "5": (4, 5, 6, 8, 9, 11, 13, 15, 18, 20, 23, 25, 27),
    "6": (6, 8, 9, 11, 13, 16, 19, 22, 25, 29, 32, 36, 40),
    "7": (10, 12, 15, 18, 21, 25, 30, 35, 40, 46, 52, 57, 63),
    "8": (14, 18, 22, 27, 33, 39, 46, 54, 63, 72, 81, 89, 97),
    "9": (25, 30, 36, 43, 52, 62, 74, 87, 100, 115, 130, 140, 155),
    "10": (40, 48, 58, 70, 84, 100, 120, 140, 160, 185, 210, 230, 250),
    "11": (60, 75, 90, 110, 130, 160, 190, 220, 250, 290, 320, 360, 400),
    "12": (100, 120, 150, 180, 210, 250, 300, 350, 400, 460, 520, 570, 630),
    "13": (140, 180, 220, 270, 330, 390, 460, 540, 630, 720, 810, 890, 970),
    "14": (250, 300, 360, 430, 520, 620, 740, 870, 1000, 1150, 1300, 1400, 1550),
    "15": (400, 480, 580, 700, 840, 1000, 1200, 1400, 1600, 1850, 2100, 2300, 2500),
    "16": (600, 750, 900, 1100, 1300, 1600, 1900, 2200, 2500, 2900, 3200, 3600, 4000),
    "17": (1000, 1200, 1500, 1800, 2100, 2500, 3000, 3500, 4000, 4600, 5200, 5700, 6300),
    "18": (1400, 1800, 2200, 2700, 3300, 3900, 4600, 5400, 6300, 7200, 8100, 8900, 9700),
}

# Intermediate ranges of the deviation tables (ISO 286-2), up to and including each limit.
_SUB = (3, 6, 10, 14, 18, 24, 30, 40, 50, 65, 80, 100, 120, 140, 160, 180, 200, 225, 250, 280, 315, 355, 400,
        450, 500)


def _by_main(values):
    """A per-main-range row spread over the intermediate ranges."""
    return tuple(values[bisect.bisect_left(_MAIN, limit)] for limit in _SUB)


# Shafts' upper deviations es (a..h, µm) per intermediate range (ISO 286-2).
_UPPER = {
    "a": (-270, -270, -280, -290, -290, -300, -300, -310, -320, -340, -360, -380, -410, -460, -520, -580, -660,
          -740, -820, -920, -1050, -1200, -1350, -1500, -1650),
    "b": (-140, -140, -150, -150, -150, -160, -160, -170, -180, -190, -200, -220, -240, -260, -280, -310, -340,
          -380, -420, -480, -540, -600, -680, -760, -840),
    "c": (-60, -70, -80, -95, -95, -110, -110, -120, -130, -140, -150, -170, -180, -200, -210, -230, -240, -260,
          -280, -300, -330, -360, -400, -440, -480),
    "d": _by_main((-20, -30, -40, -50, -65, -80, -100, -120, -145, -170, -190, -210, -230)),
    "e": _by_main((-14, -20, -25, -32, -40, -50, -60, -72, -85, -100, -110, -125, -135)),
    "f": _by_main((-6, -10, -13, -16, -20, -25, -30, -36, -43, -50, -56, -62, -68)),
    "g": _by_main((-2, -4, -5, -6, -7, -9, -10, -12, -14, -15, -17, -18, -20)),
    "h": (0,) * len(_SUB),
}
# Shafts' lower deviations ei (k..u, µm); None where the standard gives none.
_LOWER = {
    "k": _by_main((0, 1, 1, 1, 2, 2, 2, 3, 3, 4, 4, 4, 5)),  # grades 4 to 7; 0 for the others
    "m": _by_main((2, 4, 6, 7, 8, 9, 11, 13, 15, 17, 20, 21, 23)),
    "n": _by_main((4, 8, 10, 12, 15, 17, 20, 23, 27, 31, 34, 37, 40)),
    "p": _by_main((6, 12, 15, 18, 22, 26, 32, 37, 43, 50, 56, 62, 68)),
    "r": (10, 15, 19, 23, 23, 28, 28, 34, 34, 41, 43, 51, 54, 63, 65, 68, 77, 80, 84, 94, 98, 108, 114, 126, 132),
    "s": (14, 19, 23, 28, 28, 35, 35, 43, 43, 53, 59, 71, 79, 92, 100, 108, 122, 130, 140, 158, 170, 190, 208,
          232, 252),
    "t": (None, None, None, None, None, None, 41, 48, 54, 66, 75, 91, 104, 122, 134, 146, 166, 180, 196, 218, 240,
          268, 294, 330, 360),
    "u": (18, 23, 28, 33, 33, 41, 48, 60, 70, 87, 102, 124, 144, 170, 190, 210, 236, 258, 284, 315, 350, 390, 435,
          490, 540),
}
_LETTERS = tuple(_UPPER) + ("js",) + tuple(_LOWER)

_CODE = re.compile(r"^([A-Za-z]{1,2})(01|0|[1-9]|1[0-8])/([A-Za-z]{1,2})(01|0|[1-9]|1[0-8])$")


class FitError(ValueError):
    """An unknown fit code, a letter not covered, or a diameter out of range."""


@dataclass(frozen=True)
class Fit:
    code: str
    diameter: float                   # mm, nominal
    hole: Tuple[float, float]         # (lower EI, upper ES) deviations, µm
    shaft: Tuple[float, float]        # (lower ei, upper es) deviations, µm
    clearance: Tuple[float, float]    # (smallest, largest) clearance, µm; negative: interference
    fit_class: str                    # clearance | transition | interference

    def to_json(self):
        return {"code": self.code, "diameter": self.diameter, "hole": list(self.hole), "shaft": list(self.shaft),
                "clearance": list(self.clearance), "class": self.fit_class}


def _ranges(diameter):
    """(main range index, intermediate range index) of a nominal size."""
    if not diameter > 0 or diameter > MAX_DIAMETER:
        raise FitError(f"diameter {diameter:g} mm is outside ISO 286's tables covered here "
                       f"(over 0 up to {MAX_DIAMETER:g} mm)")
    return bisect.bisect_left(_MAIN, diameter), bisect.bisect_left(_SUB, diameter)


def tolerance(grade, diameter):
    """The standard tolerance ITgrade (grade "01", "0", "1".."18"), µm."""
    if str(grade) not in _IT:
        raise FitError(f"no standard tolerance grade IT{grade} (IT01, IT0, IT1 to IT18)")
    return _IT[str(grade)][_ranges(diameter)[0]]


def _js(it, grade):
    # ISO 286-2: for js7 to js11 an odd IT value (µm) is rounded down to the even one below.
    if grade in ("7", "8", "9", "10", "11") and it == int(it) and int(it) % 2:
        it -= 1
    return -it / 2, it / 2


def shaft_limits(letter, grade, diameter):
    """(ei, es) of a shaft tolerance class, µm."""
    main, sub = _ranges(diameter)
    it = tolerance(grade, diameter)
    if letter == "js":
        return _js(it, grade)
    if letter in _UPPER:
        if letter in ("a", "b") and diameter <= 1:
            raise FitError(f"shaft letter '{letter}' is not defined up to 1 mm")
        es = _UPPER[letter][sub]
        return es - it, es
    if letter in _LOWER:
        ei = _LOWER[letter][sub]
        if ei is None:
            raise FitError(f"shaft letter '{letter}' is not defined at {diameter:g} mm (from over 24 mm)")
        if letter == "k" and not (grade in ("4", "5", "6", "7") and diameter > 3):
            ei = 0  # k: the positive value only for grades 4 to 7 over 3 mm
        return ei, ei + it
    raise FitError(f"shaft letter '{letter}' is not covered (covered: {', '.join(_LETTERS)})")


def hole_limits(letter, grade, diameter):
    """(EI, ES) of a hole tolerance class, µm: the shaft deviation of the same
    letter reflected (ISO 286-1 4.2.2), with the Δ = ITn - IT(n-1) rule for
    K, M, N up to IT8 and P to U up to IT7 over 3 mm."""
    shaft = letter.lower()
    if letter != letter.upper():
        raise FitError(f"hole letter '{letter}' must be upper case")
    it = tolerance(grade, diameter)
    if shaft == "js":
        return _js(it, grade)
    if shaft in _UPPER:  # A..H: EI = -es
        ei_shaft, es_shaft = shaft_limits(shaft, grade, diameter)
        return -es_shaft, -es_shaft + it
    if shaft not in _LOWER:
        raise FitError(f"hole letter '{letter}' is not covered (covered: "
                       f"{', '.join(x.upper() for x in _LETTERS)})")
    number = -1 if grade in ("01", "0") else int(grade)
    over_3 = diameter > 3
    delta = 0.0
    if over_3 and number >= 3:  # ISO 286-1 gives Δ for IT3 to IT8
        delta = tolerance(grade, diameter) - tolerance(str(number - 1), diameter)
    if shaft == "k":
        # ES = -ei + Δ up to IT8 (ei of k4..k7); above IT8, ES = 0.
        ei = _LOWER["k"][_ranges(diameter)[1]] if over_3 else 0
        es = -ei + delta if number <= 8 else 0.0
    elif shaft in ("m", "n"):
        ei = shaft_limits(shaft, "6", diameter)[0]
        if number <= 8:
            es = -ei + delta
            if shaft == "m" and grade == "6" and 250 < diameter <= 315:
                es = -9.0  # ISO 286-2's special case of M6 over 250 up to 315 mm
        else:
            es = 0.0 if (shaft == "n" and over_3) else -ei
    else:  # P..U
        ei = shaft_limits(shaft, "6", diameter)[0]
        es = -ei + (delta if number <= 7 else 0.0)
    return es - it, es


def parse(code):
    """(hole letter, hole grade, shaft letter, shaft grade) of "H7/g6"."""
    match = _CODE.match(code.strip()) if isinstance(code, str) else None
    if not match:
        raise FitError(f"'{code}' is not an ISO 286 fit code such as H7/g6 (hole letter and grade / shaft "
                       "letter and grade)")
    hole, hole_grade, shaft, shaft_grade = match.groups()
    if hole != hole.upper() or shaft != shaft.lower():
        raise FitError(f"'{code}': the hole's letter is upper case, the shaft's lower case (e.g. H7/g6)")
    return hole, hole_grade, shaft, shaft_grade


def fit(code, diameter):
    """The Fit of `code` at the nominal `diameter` (mm). FitError for an
    unknown code, a letter not covered or a diameter out of range."""
    hole, hole_grade, shaft, shaft_grade = parse(code)
    diameter = round(float(diameter), 6)  # a radius measured as 9.9999999 is the 10 mm of the drawing
    hole_lo, hole_hi = hole_limits(hole, hole_grade, diameter)
    shaft_lo, shaft_hi = shaft_limits(shaft, shaft_grade, diameter)
    smallest, largest = hole_lo - shaft_hi, hole_hi - shaft_lo
    fit_class = "clearance" if smallest >= 0 else "interference" if largest <= 0 else "transition"
    return Fit(code=code.strip(), diameter=diameter, hole=(hole_lo, hole_hi), shaft=(shaft_lo, shaft_hi),
               clearance=(smallest, largest), fit_class=fit_class)
