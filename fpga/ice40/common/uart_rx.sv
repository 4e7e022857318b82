// SPDX-License-Identifier: Apache-2.0
// uart_rx: 8N1 UART receiver. rx_i is synchronised (2 flops), a start bit is confirmed at its middle,
// the data bits are sampled at their middles, and the byte is delivered only with a valid (high) stop
// bit; a low stop bit pulses frame_err_o instead (the byte is dropped), and the receiver then waits for
// the line to go high before it looks for a start bit (the rest of a low stop bit or a break is none).
// Parameters: ClksPerBit - clock cycles per bit (48 MHz / 115200 = 417), >= 4.
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
  localparam int CW = $clog2(ClksPerBit + 1);

  if (ClksPerBit < 4) begin : gen_bad
    initial $fatal(1, "uart_rx: ClksPerBit must be >= 4, got %0d", ClksPerBit);
  end

  logic [2:0]    sync_q;            // [2] is the synchronised line
  logic [2:0]    st_q;              // 0 idle, 1 start, 2 data, 3 stop, 4 after a framing error
  logic [CW-1:0] cnt_q;
  logic [2:0]    bit_q;
  logic [7:0]    sh_q;              // shift register; holds the byte from its stop bit to the next start

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      sync_q      <= '1;
      st_q        <= '0;
      cnt_q       <= '0;
      bit_q       <= '0;
      sh_q        <= '0;
      valid_o     <= 1'b0;
      frame_err_o <= 1'b0;
    end else begin
      sync_q      <= {sync_q[1:0], rx_i};
      valid_o     <= 1'b0;
      frame_err_o <= 1'b0;
      unique case (st_q)
        3'd0: if (!sync_q[2]) begin                         // falling edge: start bit
          st_q  <= 3'd1;
          cnt_q <= CW'(ClksPerBit / 2 - 1);
        end
        3'd1: if (cnt_q != '0) cnt_q <= cnt_q - 1'b1;
              else if (sync_q[2]) st_q <= 3'd0;             // glitch, not a start bit
              else begin st_q <= 3'd2; cnt_q <= CW'(ClksPerBit - 1); bit_q <= '0; end
        3'd2: if (cnt_q != '0) cnt_q <= cnt_q - 1'b1;
              else begin
                sh_q  <= {sync_q[2], sh_q[7:1]};            // LSB first
                cnt_q <= CW'(ClksPerBit - 1);
                bit_q <= bit_q + 1'b1;
                if (bit_q == 3'd7) st_q <= 3'd3;
              end
        3'd3: if (cnt_q != '0) cnt_q <= cnt_q - 1'b1;
              else if (sync_q[2]) begin                     // good stop bit: idle in its middle
                st_q    <= 3'd0;
                valid_o <= 1'b1;
              end else begin                                // stop bit low: wait for the line to go
                st_q        <= 3'd4;                        // high, so the rest of the low stop bit
                frame_err_o <= 1'b1;                        // (or a break) is no start bit
              end
        default: if (sync_q[2]) st_q <= 3'd0;
      endcase
    end
  end
  assign data_o = sh_q;                                     // unchanged until the next data bit
endmodule

`default_nettype wire
