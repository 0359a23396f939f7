# Recording stand-ins for the Vivado and Vitis HLS commands rfc's scripts use.
#
# Usage: tclsh vendor_stubs.tcl LOG SCRIPT
# Each vendor command appends one record to LOG: fields separated by \x1f, list items by \x1e.
# A command the stand-ins do not know fails as in tclsh ("invalid command name"), so a typo in
# a script fails the test. Checks of cells, pins and files are made by the reader of the log.

set rfc_log [open [lindex $argv 0] w]
set rfc_script [lindex $argv 1]

proc rfc_record {command args} {
    global rfc_log
    set fields [list $command]
    foreach arg $args { lappend fields [join $arg "\x1e"] }
    puts $rfc_log [join $fields "\x1f"]
}

# Commands that only configure or run: record and return nothing.
foreach command {
    create_project set_property update_ip_catalog update_compile_order create_bd_design
    apply_bd_automation assign_bd_address validate_bd_design save_bd_design launch_runs
    wait_on_run write_hw_platform open_project set_top open_solution set_part create_clock
    csynth_design export_design set_directive_interface set_directive_disaggregate
    set_directive_array_partition
} {
    proc $command {args} "rfc_record $command {*}\$args"
}

proc add_files {args} {
    set files {}
    foreach arg $args {
        if {[string index $arg 0] eq "-"} { continue }
        foreach file $arg { lappend files $file }
    }
    # -cflags takes a value: drop it from the file list.
    set index [lsearch -exact $args -cflags]
    if {$index >= 0} { set files [lsearch -all -inline -not -exact $files [lindex $args $index+1]] }
    rfc_record add_files $files
}
proc create_bd_cell {args} {
    set name [lindex $args end]
    if {[set at [lsearch -exact $args -vlnv]] >= 0} {
        rfc_record create_bd_cell ip [lindex $args $at+1] $name
    } else {
        rfc_record create_bd_cell module [lindex $args [lsearch -exact $args -reference]+1] $name
    }
    return $name
}
proc get_bd_cells {args} { return [lindex $args end] }
proc get_bd_pins {pin} { rfc_record get_bd_pins $pin; return "pin:$pin" }
proc get_bd_intf_pins {pin} { rfc_record get_bd_intf_pins $pin; return "intf:$pin" }
proc connect_bd_net {args} {
    set net ""
    if {[lindex $args 0] eq "-net"} { set net [lindex $args 1]; set args [lrange $args 2 end] }
    rfc_record connect_bd_net $net $args
}
proc connect_bd_intf_net {a b} { rfc_record connect_bd_intf_net [list $a $b] }
proc make_wrapper {args} { rfc_record make_wrapper; return "system_wrapper.vhd" }
proc get_files {args} { return [lindex $args end] }
proc current_project {} { return project }
proc current_fileset {} { return sources_1 }
proc exit {args} { rfc_record exit }

source $rfc_script
close $rfc_log
