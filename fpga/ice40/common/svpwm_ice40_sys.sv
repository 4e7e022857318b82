// SPDX-License-Identifier: Apache-2.0
// svpwm_ice40_sys: the simulatable part of the iCE40 board designs -- uart_reg_bridge (the UART frame
// protocol of fpga/ice40/README.md) in front of svpwm_mmio (the generated register map of
// docs/registers.md + the unchanged svpwm_core). The UART address byte is the register's byte offset
// (docs/registers.md, sw/svpwm_regs.h). No vendor primitives: the board tops (<board>_top) add the PLL,
// the reset synchroniser and the pins.
// Parameters:
//   ClkHz       - core clock in Hz (> 0); read back in CLK_HZ, sets the default baud divider
//   ClksPerBit  - clocks per UART bit, default ClkHz / 115200 rounded (417 at 48 MHz: 0.08 % slow);
//                 the testbench sets a small value to keep simulations short
//   TimeoutBits - inter-byte timeout of the frame protocol in bit times (1000 = 8.7 ms at 115200)
//   MinPeriod, FreqMax, GatePol - svpwm_core (via svpwm_mmio); the core's widths are those of the
//                 register map (PhaseWidth 34, FreqWidth 24, DtWidth 10) but CntWidth
//   CntWidth    - svpwm_mmio CntWidth: 16, the trimmed system 12 (f_sw >= 5.9 kHz at 48 MHz; with the
//                 board cut this is what fits the iCEstick's HX1K); read back in CONFIG.cnt_width
//   Features    - the build (svpwm_mmio, svpwm_core, svpwm_regs): a mask of svpwm_pkg::Feat* bits, e.g.
//                 svpwm_pkg::CfgFull (iCEBreaker), svpwm_pkg::CfgTiny (iCEstick); svpwmctl reads it in
//                 FEATURES.features and refuses what the board lacks
//   Trim        - 1: svpwm_mmio's board cut for the iCEstick's HX1K (no MP, CTRL.mode, CTRL.adc_trig,
//                 CARRIER, PERIOD_ACT, CMP_A..C); svpwmctl reads it in FEATURES.trim
// Pins: rx_i / tx_o UART (8N1), fault_ni active low (e.g. a gate driver's FAULT# with a pull-up) into
// the core's fault_i: the core turns the gates off combinationally, synchronises the pin itself (two
// flops, STATUS.fault) and latches the trip until CTRL.fault_clear (STATUS.tripped); gate outputs
// 1 = on (GatePol 0); led_run_o = running_o, led_fault_o = tripped_o (active high).
// Latency: a UART write is in its register the clock after the frame's checksum byte; a read samples
// the register two clocks after it.
// Restrictions: register writes take effect in the core at its next load point (docs/registers.md).
`default_nettype none

module svpwm_ice40_sys #(
  parameter logic [31:0] Features   = svpwm_pkg::CfgFull,           // the build (svpwm_pkg::Cfg*)
  parameter bit         Trim        = 1'b0,                         // the iCEstick's register cut
  parameter int         ClkHz       = 48_000_000,                   // core clock in Hz
  parameter int         ClksPerBit  = (ClkHz + 115_200 / 2) / 115_200,  // 115200 baud, rounded
  parameter int         TimeoutBits = 1000,                         // inter-byte timeout, bit times
  parameter int         MinPeriod   = svpwm_pkg::min_period(Features),
  parameter int         FreqMax     = (1 << 23) - 1,                // svpwm_core FreqMax (FreqWidth 24)
  parameter logic [1:0] GatePol     = 2'b00,                        // svpwm_core GatePol, CTRL.pol reset
  parameter int         CntWidth    = Trim ? 12 : 16                // carrier / period width (mmio)
) (
  input  logic       clk_i,           // core clock, ClkHz
  input  logic       rst_ni,          // synchronously released reset, active low
  input  logic       rx_i,            // UART from the host
  output logic       tx_o,            // UART to the host
  input  logic       fault_ni,        // fault input, active low, asynchronous
  output logic [2:0] gate_hi_o,       // {c, b, a}
  output logic [2:0] gate_lo_o,       // {c, b, a}
  output logic       led_run_o,       // gates modulating
  output logic       led_fault_o      // safe state forced (fault pin low or a latched trip)
);
  if (ClkHz <= 0) begin : gen_bad_clk_hz
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "svpwm_ice40_sys: ClkHz must be > 0, got %0d (%m)", ClkHz);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("svpwm_ice40_sys: ClkHz must be > 0, got %0d (%m)", ClkHz);
    $error("svpwm_ice40_sys: ClkHz must be > 0, got %0d", ClkHz);
`endif
  end

  // ---- UART frames -> register port ------------------------------------------------------------
  logic        req, we;
  logic [7:0]  addr;
  logic [31:0] wdata, rdata;
  logic [3:0]  be;

  uart_reg_bridge #(
    .ClksPerBit  (ClksPerBit),
    .TimeoutBits (TimeoutBits)
  ) u_bridge (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .rx_i    (rx_i),
    .tx_o    (tx_o),
    .req_o   (req),
    .we_o    (we),
    .addr_o  (addr),
    .wdata_o (wdata),
    .be_o    (be),
    .rdata_i (rdata)
  );

  // ---- generated register map + core -------------------------------------------------------------
  // outputs the board does not use (no pins for them)
  logic [2:0] unused_pole;
  logic       unused_valley, unused_peak, unused_update, unused_adc_trig, unused_sync;
  logic [1:0] unused_adc_pt;

  svpwm_mmio #(
    .AddrWidth (8),
    .AddrEarly (1'b1),              // the bridge's address byte comes a byte time before its request
    .MinPeriod (MinPeriod),
    .FreqMax   (FreqMax),
    .GatePol   (GatePol),
    .ClkHz     (ClkHz),
    .Features  (Features),
    .Trim      (Trim),
    .CntWidth  (CntWidth)
  ) u_mmio (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .req_i      (req),
    .we_i       (we),
    .addr_i     (addr),
    .wdata_i    (wdata),
    .be_i       (be),
    .rdata_o    (rdata),
    .fault_i    (!fault_ni),      // raw pin: the core gates off at once and synchronises it itself
    .sync_i     (1'b0),           // single core: CTRL.sync_en must stay 0
    .gate_hi_o  (gate_hi_o),
    .gate_lo_o  (gate_lo_o),
    .pole_o     (unused_pole),
    .valley_o   (unused_valley),
    .peak_o     (unused_peak),
    .update_o   (unused_update),
    .adc_trig_o (unused_adc_trig),
    .adc_pt_o   (unused_adc_pt),
    .sync_o     (unused_sync),
    .running_o  (led_run_o),
    .tripped_o  (led_fault_o)
  );
endmodule

`default_nettype wire
