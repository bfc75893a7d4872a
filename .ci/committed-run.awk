# A firmware run against its committed run (lab/data/*.txt), both as
# "hash SCENE METHOD 0x… pixels P instr I … stack S" lines, the committed file first:
#   awk -v scenes="lab far …" -v label="Lab #1" -f .ci/committed-run.awk COMMITTED RUN
# Every committed render of `scenes` (all scenes where it is empty) must be in the run
# with the same hash, instructions within 1 %, and a stack no deeper than committed: a
# render that needs more stack than the figures the docs quote from the committed run
# fails until the run is measured again (the script's --update). Exits 1 on any of it.
BEGIN { n = split(scenes, s, " "); for (i = 1; i <= n; i++) pick[s[i]] = 1 }
function field(name,   i) { for (i = 1; i < NF; i++) if ($i == name) return $(i + 1); return "" }
$1 != "hash" || (n > 0 && !($2 in pick)) { next }
FNR == NR {
    key = $2 " " $3
    hash[key] = $4; count[key] = field("instr"); stack[key] = field("stack"); committed++
    next
}
{
    key = $2 " " $3
    if (!(key in hash)) { print "not in the committed run: " key; bad++; next }
    seen++
    # As strings: awk would read "0x…" as a (rounded) number.
    if (("" $4) != ("" hash[key])) { print key ": hash " $4 ", committed " hash[key]; bad++ }
    change = field("instr") / count[key] - 1
    if (change > worst) worst = change
    if (-change > worst) worst = -change
    if (change > 0.01 || change < -0.01) { printf "%s: instructions %+.2f %%\n", key, 100 * change; bad++ }
    b = field("stack")
    if (b == "" || stack[key] == "") { print key ": no stack figure"; bad++ }
    else if (b + 0 > stack[key] + 0) { printf "%s: stack %d B, committed %d B\n", key, b, stack[key]; bad++ }
    else if (b + 0 < stack[key] + 0) shallower++
}
END {
    if (seen != committed) { print "renders compared: " seen ", committed: " committed; bad++ }
    if (bad) exit 1
    printf "%d %s renders: hashes equal, instructions per pixel within %.3f %% of the committed run, no stack deeper", seen, label, 100 * worst
    if (shallower) printf " (%d shallower)", shallower
    printf "\n"
}
