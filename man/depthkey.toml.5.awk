# Generates depthkey.toml(5) from config/depthkey.toml, whose comments are the
# documentation of every key: the page can never disagree with the file.
#   awk -v version=0.1.0 -f man/depthkey.toml.5.awk config/depthkey.toml
# The comment block before the first [section] (less its title paragraph)
# is the description; each
# key's comment is the comment block just above it; keys without a comment
# of their own share the one above (e.g. width and height).

function roff(text) {
	gsub(/\\/, "\\e", text)
	if (text ~ /^[.']/)
		text = "\\&" text
	return text
}

function flush(   i) {
	if (nkeys == 0)
		return
	print ".TP"
	for (i = 1; i <= nkeys; i++) {
		if (i > 1)
			print ".TQ"
		print "\\fB" roff(keys[i]) "\\fR"
	}
	print roff(comment)
	nkeys = 0
	comment = ""
}

BEGIN {
	print ".TH DEPTHKEY.TOML 5 \"2025-11-22\" \"depthkey " version "\" \"File Formats\""
	print ".SH NAME"
	print "depthkey.toml \\- configuration of the depthkey daemon"
	print ".SH SYNOPSIS"
	print ".I /etc/depthkey/depthkey.toml"
	print ".SH DESCRIPTION"
	print "The configuration of"
	print ".BR depthkeyd (8),"
	print "in TOML."
	print "It is read at start and again on"
	print ".BR \"systemctl reload depthkeyd\" ."
	print "Check a changed file before reloading with"
	print ".BR \"depthkeyd \\-\\-check\\-config /etc/depthkey/depthkey.toml\" ."
	print ".PP"
	inHeader = 1
}

/^#/ {
	line = $0
	sub(/^# ?/, "", line)
	if (inHeader) {
		# The header's first paragraph is the file's title: the NAME here.
		if (line == "")
			headerBody = 1
		else if (headerBody)
			print roff(line)
		next
	}
	if (nkeys > 0)
		flush()
	comment = comment == "" ? line : comment "\n" line
	next
}

/^\[.*\]$/ {
	flush()
	if (inHeader) {
		print ".SH KEYS"
		inHeader = 0
	}
	print ".SS " roff($0)
	next
}

/^[A-Za-z_][A-Za-z0-9_]* *=/ {
	keys[++nkeys] = $0
	next
}

/^$/ {
	next
}

END {
	flush()
	print ".SH FILES"
	print ".TP"
	print ".I /etc/depthkey/depthkey.toml"
	print "The configuration, a Debian conffile: local changes are kept when the"
	print "package is upgraded."
	print ".SH SEE ALSO"
	print ".BR depthkeyd (8)"
}
