#!/usr/bin/env python3
"""Prints two reports' whitepaper rows side by side (data.json of `tidepool report`), the verdict
agreement, the contradictions and each row's interval width. A contradiction is a row that is
firm in both runs (a claim a second run could refute: a magnitude, the opposite direction, or
a direction the figure states; `firm` in data.json) with verdicts that cannot both hold, or
`opposite` in one run and not firm in the other (stricter than issue 11's wording, which needs
both runs firm; both counts are printed). "Magnitude at band edge" claims the direction and
no magnitude, so it contradicts only `opposite`; the rows where it meets a magnitude verdict
of the other run are counted and printed apart, so a reader can count them the other way.
Also counts the rows that contention moved by more
than their stated intervals (issue 11, Deliver 1): the two runs' stated 95% intervals are
disjoint, so the shift between the estimates exceeds what both intervals together allow.
Prints figures only; never pass/fail."""
import json
import statistics
import sys

EDGE = "same-direction-magnitude-at-band-edge"


def rows(path):
    with open(path) as f:
        return {r["number"]: r for r in json.load(f)["whitepaper_rows"]}


def cell(r):
    change = r.get("measured_percent")
    ci = r.get("measured_percent_ci") or [None, None]
    if change is None or ci[0] is None:
        return "failed"
    return f"{change:+6.1f}% [{ci[0]:+.1f}, {ci[1]:+.1f}]"


def width(r):
    ci = r.get("measured_percent_ci") or [None, None]
    return None if ci[0] is None else ci[1] - ci[0]


def main():
    if len(sys.argv) != 5:
        sys.exit("usage: compare_verdicts.py LABEL_A data_a.json LABEL_B data_b.json")
    label_a, a, label_b, b = sys.argv[1], rows(sys.argv[2]), sys.argv[3], rows(sys.argv[4])
    print(f"{'#':>2}  {'whitepaper':<22} {label_a + ' change [95%]':<28} {'verdict':<38} "
          f"{label_b + ' change [95%]':<28} {'verdict':<38} agreement")
    same = contradictions = firm_pairs_differ = 0
    edge_meets_magnitude = []
    firm_big = []
    moved = []
    for n in sorted(a):
        ra, rb = a[n], b.get(n, {})
        va, vb = ra.get("verdict"), rb.get("verdict")
        fa, fb = ra.get("firm", False), rb.get("firm", False)
        if va == vb:
            same += 1
            agreement = "same"
        elif EDGE in (va, vb) and "opposite" not in (va, vb) and fa and fb:
            edge_meets_magnitude.append(n)
            agreement = "differs (magnitude at band edge claims the direction only)"
        elif (fa and fb) or "opposite" in (va, vb) and (fa or fb):
            contradictions += 1
            firm_pairs_differ += 1 if fa and fb else 0
            agreement = "CONTRADICTION" if fa and fb else "CONTRADICTION (opposite vs not firm)"
        else:
            agreement = "differs (not both firm)"
        print(f"{n:>2}  {ra.get('whitepaper_figure', '')[:22]:<22} {cell(ra):<28} {va:<38} "
              f"{cell(rb):<28} {vb:<38} {agreement}")
        ca = ra.get("measured_percent_ci") or [None, None]
        cb = rb.get("measured_percent_ci") or [None, None]
        if None not in ca and None not in cb and (ca[1] < cb[0] or cb[1] < ca[0]):
            moved.append((n, ra["measured_percent"] - rb["measured_percent"]))
        for r, f in ((ra, fa), (rb, fb)):
            change = r.get("measured_percent")
            if change is not None and abs(change) >= 3:
                firm_big.append((n, f))
    widths_a = [w for w in (width(r) for r in a.values()) if w is not None]
    widths_b = [w for w in (width(r) for r in b.values()) if w is not None]
    print(f"\nverdicts equal on {same} of {len(a)} rows; contradictions: {contradictions} "
          "(target 0)")
    print(f"  of which firm in both runs with different verdicts (the issue's wording: firm in "
          f"one run, opposite or another firm category in the other): {firm_pairs_differ}; "
          f"the rest are 'opposite' in one run and not firm in the other, which this script "
          f"counts too")
    print(f"rows where one run puts the magnitude at its band's edge and the other decides it "
          f"(not contradictions: the edge claims the direction only): "
          f"{edge_meets_magnitude if edge_meets_magnitude else 'none'}")
    print(f"rows moved by more than their stated intervals (the two intervals disjoint): "
          f"{', '.join(f'row {n} ({d:+.1f} points)' for n, d in moved) if moved else 'none'} "
          f"(target none)")
    not_firm = sorted({n for n, f in firm_big if not f})
    print(f"rows with an effect of at least 3% that are not firm in some run: "
          f"{not_firm if not_firm else 'none'} (target none)")
    for label, widths in ((label_a, widths_a), (label_b, widths_b)):
        if widths:
            print(f"{label}: median 95% interval width {statistics.median(widths):.2f} points "
                  f"(target <= 3 quiet), widest {max(widths):.2f}")


if __name__ == "__main__":
    main()
