# Sourced by the bench scripts: value FILE KEY prints KEY's value at the top
# level of a summary.json (nlohmann's two-space indent). Top level only: a
# run with precision checks also carries each check's shock_angle_deg, nested
# and listed first.
value() { grep -o "^  \"$2\": [^,}]*" "$1" | head -1 | sed 's/.*: //'; }
