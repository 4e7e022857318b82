// SPDX-License-Identifier: Apache-2.0
// uart_rx: 8N1 UART receiver. rx_i is synchronised (2 flops), a start bit is confirmed at its middle,
// the data bits are sampled at their middles, and the byte is delivered only with a valid (high) stop
// bit; a low stop bit pulses frame_err_o instead (the byte is dropped), and the receiver then waits for
// the line to go high before it looks for a start bit (the rest of a low stop bit or a break is none).
// Parameters: ClksPerBit - clock cycles per bit (48 MHz / 115200 = 417), >= 4.
// Timing: data_o, valid_o and frame_err_o are flip-flops; data_o is stable from the last data bit,
// ClksPerBit clocks before valid_o. The bit timer counts down to -1 (its sign bit ends the wait), so no
// wide compare sits between the timer and the enables.
`default_nettype none

module uart_rx #(
  parameter int ClksPerBit = 417
) (
  input  wire        clk_i,
  input  wire        rst_ni,
  input  wire        rx_i,          // serial input, idle high
  output logic [7:0] data_o,        // received byte, valid with valid_o
  output logic       valid_o,       // one-clock pulse: data_o is a new byte
  output logic       frame_err_o    // one-clock pulse: stop bit was low (byte dropped)
);
  localparam int CW = $clog2(ClksPerBit) + 1;   // ClksPerBit - 2 and a sign bit

  if (ClksPerBit < 4) begin : gen_bad
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "uart_rx: ClksPerBit must be >= 4, got %0d (%m)", ClksPerBit);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("uart_rx: ClksPerBit must be >= 4, got %0d (%m)", ClksPerBit);
    $error("uart_rx: ClksPerBit must be >= 4, got %0d", ClksPerBit);
`endif
  end

  // RxWait: after a framing error, until the line is high
  typedef enum logic [2:0] {RxIdle, RxStart, RxData, RxStop, RxWait} rx_state_e;
  rx_state_e     st_d, st_q;
  logic [2:0]    sync_d, sync_q;    // [2] is the synchronised line
  logic [CW-1:0] cnt_d, cnt_q;      // clocks to wait minus 2: the wait ends at -1 (cnt_q[CW-1])
  logic [2:0]    bit_d, bit_q;
  logic [7:0]    sh_d, sh_q;        // shift register; holds the byte from its stop bit to the next start
  logic          valid_d, valid_q, ferr_d, ferr_q;
  logic          line, done;

  assign line = sync_q[2];
  assign done = cnt_q[CW-1];

  always_comb begin
    st_d    = st_q;
    sync_d  = {sync_q[1:0], rx_i};
    cnt_d   = cnt_q - 1'b1;           // runs freely: loaded before every wait
    bit_d   = bit_q;
    sh_d    = sh_q;
    valid_d = 1'b0;
    ferr_d  = 1'b0;
    unique case (st_q)
      RxIdle: if (!line) begin                              // falling edge: start bit
        st_d  = RxStart;
        cnt_d = CW'(ClksPerBit / 2 - 2);
      end
      RxStart: if (done) begin
        if (line) st_d = RxIdle;                            // glitch, not a start bit
        else begin
          st_d  = RxData;
          cnt_d = CW'(ClksPerBit - 2);
          bit_d = '0;
        end
      end
      RxData: if (done) begin
        sh_d  = {line, sh_q[7:1]};                          // LSB first
        cnt_d = CW'(ClksPerBit - 2);
        bit_d = bit_q + 1'b1;
        if (bit_q == 3'd7) st_d = RxStop;
      end
      RxStop: if (done) begin
        if (line) begin                                     // good stop bit: idle in its middle
          st_d    = RxIdle;
          valid_d = 1'b1;
        end else begin                                      // stop bit low: wait for the line to go
          st_d   = RxWait;                                  // high, so the rest of the low stop bit
          ferr_d = 1'b1;                                    // (or a break) is no start bit
        end
      end
      default: if (line) st_d = RxIdle;                     // RxWait
    endcase
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      st_q    <= RxIdle;
      sync_q  <= '1;
      cnt_q   <= '0;
      bit_q   <= '0;
      sh_q    <= '0;
      valid_q <= 1'b0;
      ferr_q  <= 1'b0;
    end else begin
      st_q    <= st_d;
      sync_q  <= sync_d;
      cnt_q   <= cnt_d;
      bit_q   <= bit_d;
      sh_q    <= sh_d;
      valid_q <= valid_d;
      ferr_q  <= ferr_d;
    end
  end

  assign data_o      = sh_q;                                // unchanged until the next data bit
  assign valid_o     = valid_q;
  assign frame_err_o = ferr_q;
endmodule

`default_nettype wire
