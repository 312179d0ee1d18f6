"""A problem set asks no number that the constraints fix: the distance of centres ρ = R + r of a sphere rolling
on a fixed sphere (and its rate ρ̇ = 0) is listed as fixed by the contact, not keyed as a question."""

import math
import xml.etree.ElementTree as ET

from rigidkin.grading.exports import as_moodle, as_prairielearn
from rigidkin.grading.variants import make_set


def test_a_coordinate_fixed_by_the_contact_is_no_question(tmp_path):
    ps = make_set("sphere-on-sphere", 2, 0, {})
    for v in ps.variants:
        symbols = [k.symbol for k in v.keys]
        assert symbols == ["θ", "φ", "θ̇", "φ̇"], symbols
        assert "leaves_sphere: ρ is not asked (ρ = R + r, fixed by the constraint P)" in v.notes
        assert "leaves_sphere: ρ̇ is not asked (ρ̇ = 0, fixed by the constraint P)" in v.notes
        # what is still asked is right: a sphere rolling off a sphere leaves it at cos φ = 10/17 (by hand,
        # energy and N = 0 with the rolling sphere's k² = 2/5 r²)
        phi = next(k for k in v.keys if k.symbol == "φ")
        assert math.isclose(phi.value, math.acos(10 / 17), rel_tol=1e-9)
    texts = [q.find("questiontext/text").text for q in
             ET.fromstring(as_moodle(ps)).findall("question[@type='numerical']")]
    assert len(texts) == 8 and not any("give ρ" in x for x in texts) and any("give φ " in x for x in texts)
    for folder in as_prairielearn(ps, tmp_path / "pl"):
        html = (folder / "question.html").read_text(encoding="utf-8")
        assert html.count("<pl-number-input") == 4 and "give ρ" not in html


def test_a_problem_with_no_fixed_coordinate_keeps_every_key():
    ps = make_set("disk-in-track", 1, 0, {})
    assert not any("is not asked" in n for n in ps.variants[0].notes)
