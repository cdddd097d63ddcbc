#!/usr/bin/perl
# Writes the man page of rcm from what `rcm --help` prints, so that the page
# says what the program says. help2man reads the option lists of the Qt
# programs (gcs, uasim, satmodem) but not rcm's layout, which is:
#   Usage:               followed by indented synopsis lines
#   TERM  text           a command or option, its text on lines indented by 8,
#                        examples on lines indented further (kept as they are)
#   Exit status: text    and   Example:  followed by indented lines
# The include file adds hand-written sections, as help2man's --include does:
# a line "[SECTION]" starts one, the lines after it are roff.
#
# Usage: rcm-help-to-man.pl PROGRAM NAME-LINE VERSION INCLUDE OUTPUT
use strict;
use warnings;
use POSIX qw(strftime);

my ($program, $name, $version, $include, $output) = @ARGV;
die "usage: $0 PROGRAM NAME-LINE VERSION INCLUDE OUTPUT\n" unless defined $output;

open(my $help, '-|', $program, '--help') or die "$0: cannot run $program: $!\n";
my @lines = <$help>;
close($help) or die "$0: $program --help failed\n";
chomp @lines;

# Text for roff: backslashes and hyphens escaped, no line taken for a request.
sub roff {
    my ($t) = @_;
    $t =~ s/\\/\\e/g;
    $t =~ s/-/\\-/g;
    $t =~ s/^([.'])/\\&$1/;
    return $t;
}

my $date = strftime('%B %Y', gmtime($ENV{SOURCE_DATE_EPOCH} // time));
my $base = $program;
$base =~ s{.*/}{};
my @out = (".\\\" Generated from `$base --help` by cmake/rcm-help-to-man.pl; edit the help text or the include file.",
           ".TH \U$base\E 1 \"$date\" \"$base $version\" \"User Commands\"",
           '.SH NAME', roff("$base - $name"));

my $mode = '';      # what the lines being read are: synopsis, term, example
my $verbatim = 0;   # inside .nf
my $exit = 0;       # inside the exit status section
sub fill { if ($verbatim) { push @out, '.fi'; $verbatim = 0; } }
sub literal { unless ($verbatim) { push @out, '.nf'; $verbatim = 1; } }

for my $line (@lines) {
    if ($line eq '') {
        fill();
        push @out, '.PP' if $mode eq 'term' || $exit;
        next;
    }
    if ($line =~ /^Usage:\s*$/) {
        push @out, '.SH SYNOPSIS';
        $mode = 'synopsis';
        literal();
    } elsif ($line =~ /^Exit status:\s*(.*)$/) {
        fill();
        push @out, '.SH "EXIT STATUS"', roff(ucfirst $1);
        ($mode, $exit) = ('', 1);
    } elsif ($line =~ /^Examples?:\s*$/) {
        fill();
        push @out, '.SH EXAMPLES';
        ($mode, $exit) = ('example', 0);
        literal();
    } elsif ($line =~ /^(\S.*?)  +(\S.*)$/) {
        fill();
        push @out, '.SH DESCRIPTION' unless $mode eq 'term';
        push @out, '.TP', '.B ' . roff($1), roff($2);
        ($mode, $exit) = ('term', 0);
    } elsif ($mode eq 'synopsis' || $mode eq 'example') {
        (my $t = $line) =~ s/^  //;
        push @out, roff($t);
    } elsif ($mode eq 'term' && $line =~ /^ {9,}(.*)$/) {
        literal();
        push @out, roff("  $1");
    } elsif ($line =~ /^\s*(.*)$/) {
        fill();
        push @out, roff($1);
    }
}
fill();

open(my $extra, '<', $include) or die "$0: cannot read $include: $!\n";
while (my $line = <$extra>) {
    chomp $line;
    next if $line =~ /^#/;
    $line =~ s/^\[(.*)\]$/.SH "$1"/;
    push @out, $line;
}
close($extra);

open(my $page, '>', $output) or die "$0: cannot write $output: $!\n";
print $page map { "$_\n" } @out;
close($page) or die "$0: cannot write $output: $!\n";
